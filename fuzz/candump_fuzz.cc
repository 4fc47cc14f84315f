// candump logs (drivers/can/candump_log.h), as fleetmap reads recorded CAN traffic: any text as
// a whole log. Every frame the parser accepts must be valid, and formatting it as a candump
// line and parsing that line again must give the same frame.
#include <cmath>

#include "drivers/can/candump_log.h"
#include "fuzz/fuzz_check.h"

namespace fleetmap::fuzz {
namespace {

bool SameFrame(const drivers::can::CanFrame& a, const drivers::can::CanFrame& b) {
  return a.id == b.id && a.extended == b.extended && a.rtr == b.rtr && a.error == b.error &&
         a.fd == b.fd && a.fd_flags == b.fd_flags && a.len == b.len && a.len8_dlc == b.len8_dlc &&
         (a.rtr || std::equal(a.data.begin(), a.data.begin() + a.len, b.data.begin()));
}

}  // namespace
}  // namespace fleetmap::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap::drivers::can;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const CandumpLog log = ParseCandumpLog(text);
  FUZZ_REQUIRE(log.stats.records + log.stats.ignored + log.stats.malformed == log.stats.lines);
  for (const CandumpRecord& r : log.records) {
    FUZZ_REQUIRE(r.frame.Validate().ok());
    auto back = ParseCandumpLine(FormatCandumpLine(r));
    FUZZ_REQUIRE(back.ok() && back->interface == r.interface &&
                 fleetmap::fuzz::SameFrame(back->frame, r.frame));
    FUZZ_REQUIRE(std::abs(back->frame.stamp_s - r.frame.stamp_s) <=
                 1e-6 + 1e-15 * std::abs(r.frame.stamp_s));
  }
  return 0;
}
