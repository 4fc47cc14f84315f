// The aggregator's temporary-map assembler fed a sequence of TEMPMAP tiles (concatenated
// tempmap_tile_t payloads, checksums repaired so that tiles reach the assembler): tiles of
// several maps interleaved, repeated, contradicting each other, beyond the pending-map limit.
#include <set>

#include "core/codec/temp_map_tiles.h"
#include "fuzz/fuzz_check.h"
#include "fuzz/lcm_bytes.h"
#include "lcmtypes/transport_convert.h"

namespace fleetmap::fuzz {
namespace {

// Small limits so that short inputs reach them.
core::AssemblerOptions Options() {
  core::AssemblerOptions o;
  o.max_pending_maps = 3;
  o.max_tiles = 64;
  o.max_map_cells = 512 * 512;
  return o;
}

void CheckReceived(const core::TempMapAssembler& assembler, const core::TempMapTile& tile) {
  const std::vector<int32_t> received = assembler.Received(tile.vehicle_id, tile.sequence);
  FUZZ_REQUIRE(std::set<int32_t>(received.begin(), received.end()).size() == received.size());
  for (const int32_t i : received) FUZZ_REQUIRE(i >= 0 && i < tile.count);
}

}  // namespace
}  // namespace fleetmap::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap;
  const core::AssemblerOptions options = fuzz::Options();
  core::TempMapAssembler assembler(options);
  size_t pos = 0;
  while (fuzz::StartsWithType<fleetmap::tempmap_tile_t>(data, size, pos)) {
    auto msg = fuzz::DecodeAt<fleetmap::tempmap_tile_t>(data, size, pos);
    if (!msg.ok()) break;
    fuzz::RepairTileMessage(msg->tile);
    core::Result<core::TempMapTile> tile = lcmtypes::FromMessage(*msg);
    if (!tile.ok()) continue;
    core::Result<std::optional<core::TempMap>> map = assembler.Add(*tile);
    FUZZ_REQUIRE(assembler.pending() <= size_t(options.max_pending_maps));
    if (map.ok() && map->has_value()) {
      FUZZ_REQUIRE((*map)->Validate().ok());
      FUZZ_REQUIRE((*map)->grid.geometry().num_cells() <= options.max_map_cells);
      FUZZ_REQUIRE(assembler.Received(tile->vehicle_id, tile->sequence).empty());
    } else if (map.ok()) {
      fuzz::CheckReceived(assembler, *tile);
    }
  }
  return 0;
}
