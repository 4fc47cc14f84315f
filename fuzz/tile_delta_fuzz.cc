// Tile deltas (core/tile_delta.h): a list of tiles (tile_list_input.h, checksums repaired)
// applied to a grid with ApplyTiles, which must apply all of them or none. When they apply,
// the delta EncodeChangedTiles computes between the grid before and after must reproduce the
// grid after, in the packing's terms.
#include "core/tile_delta.h"
#include "fuzz/checksum_repair.h"
#include "fuzz/fuzz_check.h"
#include "fuzz/tile_list_input.h"

namespace fleetmap::fuzz {
namespace {

// A grid with some of every state, so that tiles change something.
core::OccupancyGrid Before(int width, int height) {
  core::OccupancyGrid grid(core::GridGeometry(0.05, width, height, core::Pose2(-1, 2, 0.5)));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const int k = (x * 7 + y * 13) % 5;
      grid.SetLogOdds({x, y}, k == 0 ? 4.6f : k == 1 ? -4.6f : k == 2 ? 0.8f : 0.0f);
    }
  }
  return grid;
}

void CheckDelta(const core::OccupancyGrid& before, const core::OccupancyGrid& after,
                int tile_size_cells, core::CellPacking packing) {
  core::TileOptions options;
  options.tile_size_cells = tile_size_cells;
  options.codec.packing = packing;
  options.codec.level = 1;
  core::OccupancyGrid replayed = before;
  FUZZ_REQUIRE(
      core::ApplyTiles(core::EncodeChangedTiles(before, after, options), tile_size_cells, replayed)
          .ok());
  const core::CellWindow all = after.geometry().full_window();
  FUZZ_REQUIRE(core::PackCells(replayed, all, packing) == core::PackCells(after, all, packing));
}

}  // namespace
}  // namespace fleetmap::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap;
  fuzz::TileListInput in = fuzz::ReadTileList(data, size);
  for (core::EncodedTile& t : in.tiles) fuzz::RepairTrailingCrc32(t.frame);
  const core::OccupancyGrid before = fuzz::Before(in.width_cells, in.height_cells);
  core::OccupancyGrid after = before;
  if (!core::ApplyTiles(in.tiles, in.tile_size_cells, after).ok()) {
    FUZZ_REQUIRE(after.cells() == before.cells());  // all or nothing
    return 0;
  }
  fuzz::CheckDelta(before, after, in.tile_size_cells, core::CellPacking::kTriState2Bit);
  fuzz::CheckDelta(before, after, in.tile_size_cells, core::CellPacking::kLogOddsInt8);
  return 0;
}
