// The S300/S3000 serial output (drivers/sick/s300_telegram.h). Byte 0 picks the size of the
// pieces the serial port delivers (1 + b * b bytes); the rest is
//   - parsed as one telegram, as it is and with its CRC repaired: a telegram that parses
//     re-encodes to the same bytes and converts to a valid LaserScan;
//   - fed to the stream splitter piece by piece, which resynchronises after garbage.
#include "drivers/sick/s300_telegram.h"
#include "fuzz/checksum_repair.h"
#include "fuzz/fuzz_check.h"

namespace fleetmap::fuzz {
namespace {

void CheckTelegram(const drivers::sick::S300Telegram& t, const std::vector<uint8_t>& bytes) {
  FUZZ_REQUIRE(drivers::sick::EncodeS300Telegram(t) == bytes);
  auto scan = drivers::sick::S300ToLaserScan(t, {}, 0.0);
  if (scan.ok()) FUZZ_REQUIRE(scan->Validate().ok());
}

void ParseOne(const std::vector<uint8_t>& bytes) {
  auto t = drivers::sick::ParseS300Telegram(bytes.data(), bytes.size());
  if (t.ok()) CheckTelegram(*t, bytes);
}

}  // namespace
}  // namespace fleetmap::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap;
  if (size < 1) return 0;
  std::vector<uint8_t> bytes(data + 1, data + size);
  fuzz::ParseOne(bytes);
  std::vector<uint8_t> repaired = bytes;
  if (fuzz::RepairS300Crc(repaired)) fuzz::ParseOne(repaired);

  const size_t piece_bytes = 1 + data[0] * data[0];
  drivers::sick::S300StreamSplitter splitter;
  for (size_t at = 0; at < bytes.size(); at += piece_bytes) {
    const size_t n = std::min(piece_bytes, bytes.size() - at);
    splitter.Feed(bytes.data() + at, n);
    while (std::optional<drivers::sick::S300Telegram> t = splitter.Next()) {
      FUZZ_REQUIRE(t->beams.size() <= drivers::sick::kS300MaxBeams);
    }
  }
  return 0;
}
