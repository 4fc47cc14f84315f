// Temporary-map files (core/map/temp_map_file.h), what an agent reads back from its outbox after a
// restart: any bytes, as they are and with the file's CRC repaired. A file that decodes must
// re-encode to a file that decodes to the same map; a second round trip changes nothing.
#include "core/map/temp_map_file.h"
#include "fuzz/checksum_repair.h"
#include "fuzz/fuzz_check.h"

namespace fleetmap::fuzz {
namespace {

bool SamePose(const core::Pose2& a, const core::Pose2& b) {
  return a.x_m == b.x_m && a.y_m == b.y_m && a.theta_rad == b.theta_rad;
}

core::TempMap RoundTrip(const core::TempMap& map) {
  const std::vector<uint8_t> bytes = core::EncodeTempMap(map);
  core::Result<core::TempMap> back = core::DecodeTempMap(bytes.data(), bytes.size());
  FUZZ_REQUIRE(back.ok());
  FUZZ_REQUIRE(back->vehicle_id == map.vehicle_id && back->sequence == map.sequence);
  FUZZ_REQUIRE(back->start_s == map.start_s && back->end_s == map.end_s);
  FUZZ_REQUIRE(back->grid.geometry().width() == map.grid.geometry().width() &&
               back->grid.geometry().height() == map.grid.geometry().height());
  FUZZ_REQUIRE(back->grid.cells() == map.grid.cells());
  return std::move(back).value();
}

void Check(const core::TempMap& map) {
  FUZZ_REQUIRE(map.Validate().ok());
  const core::TempMap once = RoundTrip(map);
  const core::TempMap twice = RoundTrip(once);
  FUZZ_REQUIRE(SamePose(once.anchor_in_map, twice.anchor_in_map));
}

}  // namespace
}  // namespace fleetmap::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap;
  core::Result<core::TempMap> map = core::DecodeTempMap(data, size);
  if (map.ok()) fuzz::Check(*map);
  std::vector<uint8_t> repaired(data, data + size);
  if (fuzz::RepairTrailingCrc32(repaired)) {
    map = core::DecodeTempMap(repaired.data(), repaired.size());
    if (map.ok()) fuzz::Check(*map);
  }
  return 0;
}
