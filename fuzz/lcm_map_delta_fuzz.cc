// MAP_DELTA as a vehicle receives it: one map_delta_t payload, decoded, validated
// (lcmtypes/transport_convert.h) and applied to a replica seeded with a small map at the
// delta's base version, so that a one-tile delta is applied at once.
#include "core/map/map_replica.h"
#include "fuzz/fuzz_check.h"
#include "fuzz/lcm_bytes.h"
#include "lcmtypes/convert.h"
#include "lcmtypes/transport_convert.h"

namespace fleetmap::fuzz {
namespace {

// 100 x 70 cells at 64-cell tiles: 2 x 2 tiles, the edge ones clipped (as the tests' map).
core::OccupancyGrid SeedMap() {
  core::OccupancyGrid grid(core::GridGeometry(0.05, 100, 70, core::Pose2(1, 1, 0)));
  grid.SetState({10, 10}, core::CellState::kOccupied);
  grid.SetState({80, 60}, core::CellState::kFree);
  return grid;
}

void Handle(const fleetmap::map_delta_t& msg) {
  core::Result<core::DeltaTile> tile = lcmtypes::FromMessage(msg);
  if (!tile.ok()) return;
  core::MapReplica replica;
  const int32_t base = tile->base_version < 0 ? 0 : tile->base_version;
  FUZZ_REQUIRE(replica.Seed(SeedMap(), base).ok());
  core::Result<bool> advanced = replica.AddDeltaTile(*tile);
  if (advanced.ok() && *advanced) {
    FUZZ_REQUIRE(replica.has_map() && replica.version() == int64_t{base} + 1);
    FUZZ_REQUIRE(replica.map().geometry() == SeedMap().geometry());
  }
  // A delta that cannot be applied drops the map (a keyframe is requested), never half of it.
  if (replica.has_map() && replica.version() == base) {
    FUZZ_REQUIRE(replica.map().cells() == SeedMap().cells());
  }
}

}  // namespace
}  // namespace fleetmap::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap;
  auto msg = lcmtypes::Decode<fleetmap::map_delta_t>(data, static_cast<int>(size));
  if (!msg.ok()) return 0;
  fuzz::Handle(*msg);
  if (fuzz::RepairTileMessage(msg->tile)) fuzz::Handle(*msg);
  return 0;
}
