// SCAN_<vehicle>: one laser_scan_t payload, decoded and validated (lcmtypes/convert.h). An
// accepted scan must survive the way back to the wire unchanged.
#include <cstring>

#include "fuzz/fuzz_check.h"
#include "fuzz/lcm_bytes.h"
#include "lcmtypes/convert.h"

namespace fleetmap::fuzz {
namespace {

bool SameFloats(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

}  // namespace
}  // namespace fleetmap::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap;
  auto msg = lcmtypes::Decode<fleetmap::laser_scan_t>(data, static_cast<int>(size));
  if (!msg.ok()) return 0;
  core::Result<core::LaserScan> scan = lcmtypes::FromMessage(*msg);
  if (!scan.ok()) return 0;
  FUZZ_REQUIRE(scan->Validate().ok() && scan->size() <= size_t{lcmtypes::kMaxBeams});
  const std::string bytes = fuzz::EncodeLcm(lcmtypes::ToMessage(*scan, msg->vehicle_id, msg->seq));
  auto again =
      lcmtypes::Decode<fleetmap::laser_scan_t>(bytes.data(), static_cast<int>(bytes.size()));
  FUZZ_REQUIRE(again.ok());
  core::Result<core::LaserScan> back = lcmtypes::FromMessage(*again);
  FUZZ_REQUIRE(back.ok() && fuzz::SameFloats(back->ranges_m, scan->ranges_m) &&
               fuzz::SameFloats(back->intensities, scan->intensities) &&
               back->angle_increment_rad == scan->angle_increment_rad);
  return 0;
}
