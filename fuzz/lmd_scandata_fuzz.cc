// LMDscandata payloads (drivers/sick/scan_telegram_codec.h) without framing, in both protocols:
// byte 0 picks CoLa-A (even) or CoLa-B (odd), the rest is the payload. A telegram that parses
// must re-encode to a payload that parses to the same telegram (encode, parse, encode gives
// the same bytes), and convert to a LaserScan or say why not.
#include <string>

#include "drivers/sick/scan_conversion.h"
#include "drivers/sick/scan_telegram_codec.h"
#include "fuzz/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap::drivers::sick;
  if (size < 1) return 0;
  const ColaProtocol protocol = data[0] % 2 ? ColaProtocol::kColaB : ColaProtocol::kColaA;
  const std::string_view payload(reinterpret_cast<const char*>(data) + 1, size - 1);
  fleetmap::core::Result<ScanTelegram> telegram = ParseScanTelegram(payload, protocol);
  if (!telegram.ok()) return 0;
  const std::string once = EncodeScanTelegram(*telegram, protocol);
  fleetmap::core::Result<ScanTelegram> again = ParseScanTelegram(once, protocol);
  FUZZ_REQUIRE(again.ok());
  FUZZ_REQUIRE(EncodeScanTelegram(*again, protocol) == once);
  auto scan = ToLaserScan(*telegram, {}, 0.0);
  if (scan.ok()) (void)scan->Validate();
  return 0;
}
