// A vehicle's map replica fed a sequence of MAP_KEYFRAME and MAP_DELTA tiles (concatenated
// map_keyframe_t / map_delta_t payloads, told apart by their fingerprints, checksums repaired):
// keyframes interrupted by newer ones, deltas out of order, gaps, duplicates, corrupt tiles.
// A replica that starts with a delta is seeded with a small static map at version 0.
#include "core/map/map_replica.h"
#include "fuzz/fuzz_check.h"
#include "fuzz/lcm_bytes.h"
#include "lcmtypes/transport_convert.h"

namespace fleetmap::fuzz {
namespace {

// Made once: filling its 7000 cells took a quarter of every execution; a copy is a memcpy.
const core::OccupancyGrid& SeedMap() {
  static const core::OccupancyGrid grid = [] {
    core::OccupancyGrid g(core::GridGeometry(0.05, 100, 70, core::Pose2(1, 1, 0)));
    g.SetState({10, 10}, core::CellState::kOccupied);
    return g;
  }();
  return grid;
}

void AddKeyframe(const uint8_t* data, size_t size, size_t& pos, core::MapReplica& replica) {
  auto msg = DecodeAt<fleetmap::map_keyframe_t>(data, size, pos);
  if (!msg.ok()) return pos = size, void();
  RepairTileMessage(msg->tile);
  core::Result<core::KeyframeTile> tile = lcmtypes::FromMessage(*msg);
  if (!tile.ok()) return;
  core::Result<bool> done = replica.AddKeyframeTile(*tile);
  if (done.ok() && *done) {
    FUZZ_REQUIRE(replica.has_map() && replica.version() >= tile->version);
    FUZZ_REQUIRE(replica.map().geometry() == tile->geometry);
  }
}

void AddDelta(const uint8_t* data, size_t size, size_t& pos, core::MapReplica& replica) {
  auto msg = DecodeAt<fleetmap::map_delta_t>(data, size, pos);
  if (!msg.ok()) return pos = size, void();
  RepairTileMessage(msg->tile);
  core::Result<core::DeltaTile> tile = lcmtypes::FromMessage(*msg);
  if (!tile.ok()) return;
  const int32_t before = replica.has_map() ? replica.version() : -1;
  core::Result<bool> advanced = replica.AddDeltaTile(*tile);
  if (advanced.ok() && *advanced && replica.has_map()) {
    FUZZ_REQUIRE(replica.version() > before);
  }
}

}  // namespace
}  // namespace fleetmap::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap;
  core::MapReplica replica(/*max_buffered_versions=*/4);
  if (fuzz::StartsWithType<fleetmap::map_delta_t>(data, size, 0)) {
    FUZZ_REQUIRE(replica.Seed(fuzz::SeedMap(), 0).ok());
  }
  size_t pos = 0;
  while (pos < size) {
    if (fuzz::StartsWithType<fleetmap::map_keyframe_t>(data, size, pos)) {
      fuzz::AddKeyframe(data, size, pos, replica);
    } else if (fuzz::StartsWithType<fleetmap::map_delta_t>(data, size, pos)) {
      fuzz::AddDelta(data, size, pos, replica);
    } else {
      break;
    }
    if (replica.has_map())
      FUZZ_REQUIRE(replica.version() >= 0 && replica.map().geometry().Validate().ok());
  }
  return 0;
}
