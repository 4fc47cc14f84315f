// TEMPMAP_<vehicle> as the aggregator receives it: one tempmap_tile_t payload, decoded,
// validated (lcmtypes/transport_convert.h) and handed to a temporary-map assembler.
#include "core/codec/temp_map_tiles.h"
#include "fuzz/fuzz_check.h"
#include "fuzz/lcm_bytes.h"
#include "lcmtypes/convert.h"
#include "lcmtypes/transport_convert.h"

namespace fleetmap::fuzz {
namespace {

void Handle(const fleetmap::tempmap_tile_t& msg) {
  core::Result<core::TempMapTile> tile = lcmtypes::FromMessage(msg);
  if (!tile.ok()) return;
  FUZZ_REQUIRE(!tile->vehicle_id.empty() && tile->anchor_in_map.IsFinite());
  core::TempMapAssembler assembler;
  core::Result<std::optional<core::TempMap>> map = assembler.Add(*tile);
  if (map.ok() && map->has_value()) FUZZ_REQUIRE((*map)->Validate().ok());
}

}  // namespace
}  // namespace fleetmap::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap;
  auto msg = lcmtypes::Decode<fleetmap::tempmap_tile_t>(data, static_cast<int>(size));
  if (!msg.ok()) return 0;
  fuzz::Handle(*msg);
  if (fuzz::RepairTileMessage(msg->tile)) fuzz::Handle(*msg);
  return 0;
}
