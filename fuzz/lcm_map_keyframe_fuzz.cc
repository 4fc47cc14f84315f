// MAP_KEYFRAME as a vehicle receives it: one map_keyframe_t payload, decoded, validated
// (lcmtypes/transport_convert.h) and handed to a map replica. A keyframe of one tile completes
// the map, so the replica's whole keyframe path runs.
#include "core/map/map_replica.h"
#include "fuzz/fuzz_check.h"
#include "fuzz/lcm_bytes.h"
#include "lcmtypes/convert.h"
#include "lcmtypes/transport_convert.h"

namespace fleetmap::fuzz {
namespace {

void Handle(const fleetmap::map_keyframe_t& msg) {
  core::Result<core::KeyframeTile> tile = lcmtypes::FromMessage(msg);
  if (!tile.ok()) return;
  FUZZ_REQUIRE(tile->geometry.Validate().ok());
  core::MapReplica replica;
  core::Result<bool> done = replica.AddKeyframeTile(*tile);
  if (done.ok() && *done) {
    FUZZ_REQUIRE(replica.has_map() && replica.version() == tile->version);
    FUZZ_REQUIRE(replica.map().geometry() == tile->geometry);
  }
  if (!done.ok()) FUZZ_REQUIRE(!replica.has_map());
}

}  // namespace
}  // namespace fleetmap::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap;
  auto msg = lcmtypes::Decode<fleetmap::map_keyframe_t>(data, static_cast<int>(size));
  if (!msg.ok()) return 0;
  fuzz::Handle(*msg);
  if (fuzz::RepairTileMessage(msg->tile)) fuzz::Handle(*msg);
  return 0;
}
