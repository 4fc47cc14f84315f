// Tile deltas (core/codec/tile_delta.h): a list of tiles (tile_list_input.h, checksums repaired)
// applied to a grid with ApplyTiles, which must apply all of them or none. When they apply,
// the delta EncodeChangedTiles computes between the grid before and after must reproduce the
// grid after, in the packing's terms.
#include <cstring>

#include "core/codec/tile_delta.h"
#include "fuzz/checksum_repair.h"
#include "fuzz/fuzz_check.h"
#include "fuzz/tile_list_input.h"

namespace fleetmap::fuzz {
namespace {

constexpr int kMaxSide = 256;  // tile_list_input.h: 1 + one byte

core::GridGeometry GeometryOf(int width, int height) {
  return core::GridGeometry(0.05, width, height, core::Pose2(-1, 2, 0.5));
}

// A grid with some of every state, so that tiles change something. The pattern is made once
// for the largest grid and copied row by row, and the last grid is kept (mutations mostly keep
// the size): setting up to 65536 cells one by one took half of every execution.
const core::OccupancyGrid& Before(int width, int height) {
  static core::OccupancyGrid last;
  if (last.geometry().width() == width && last.geometry().height() == height) return last;
  static const core::OccupancyGrid pattern = [] {
    core::OccupancyGrid grid(GeometryOf(kMaxSide, kMaxSide));
    for (int y = 0; y < kMaxSide; ++y) {
      for (int x = 0; x < kMaxSide; ++x) {
        const int k = (x * 7 + y * 13) % 5;
        grid.SetLogOdds({x, y}, k == 0 ? 4.6f : k == 1 ? -4.6f : k == 2 ? 0.8f : 0.0f);
      }
    }
    return grid;
  }();
  last = core::OccupancyGrid(GeometryOf(width, height));
  for (int y = 0; y < height; ++y) {
    std::memcpy(last.mutable_cells().data() + size_t(y) * width,
                pattern.cells().data() + size_t(y) * kMaxSide, size_t(width) * sizeof(float));
  }
  return last;
}

bool SameCells(const core::OccupancyGrid& a, const core::OccupancyGrid& b) {
  return a.cells().size() == b.cells().size() &&
         std::memcmp(a.cells().data(), b.cells().data(), a.cells().size() * sizeof(float)) == 0;
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
  const core::OccupancyGrid& before = fuzz::Before(in.width_cells, in.height_cells);
  core::OccupancyGrid after = before;
  if (!core::ApplyTiles(in.tiles, in.tile_size_cells, after).ok()) {
    FUZZ_REQUIRE(fuzz::SameCells(after, before));  // all or nothing, to the bit
    return 0;
  }
  fuzz::CheckDelta(before, after, in.tile_size_cells, core::CellPacking::kTriState2Bit);
  fuzz::CheckDelta(before, after, in.tile_size_cells, core::CellPacking::kLogOddsInt8);
  return 0;
}
