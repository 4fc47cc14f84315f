// Seeds of the map transport targets: what the agent and the aggregator actually send, made
// by the same encoders (SplitTempMap, EncodeAllTiles, EncodeChangedTiles, ToMessage).
#include "core/codec/temp_map_tiles.h"
#include "core/map/temp_map_file.h"
#include "fuzz/lcm_bytes.h"
#include "fuzz/seed_sources.h"
#include "fuzz/tile_list_input.h"
#include "lcmtypes/transport_convert.h"

namespace fleetmap::fuzz {
namespace {

constexpr int64_t kUtime = 1'700'000'000'000'000;

// A grid with every state and some in-between evidence, like a real temporary map.
core::OccupancyGrid PatternGrid(int width, int height, core::Pose2 origin = {}) {
  core::OccupancyGrid grid(core::GridGeometry(0.05, width, height, origin));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const int k = (x / 3 + y / 5) % 6;
      if (k < 4) grid.SetLogOdds({x, y}, k == 0 ? 4.6f : k == 1 ? -4.6f : k == 2 ? 1.2f : -0.7f);
    }
  }
  return grid;
}

core::TempMap SampleTempMap(int width, int height, int32_t sequence) {
  core::TempMap map;
  map.vehicle_id = "vehicle_a";
  map.sequence = sequence;
  map.anchor_in_map = core::Pose2(12.5, 4.25, 0.3);
  Eigen::Matrix3d covariance;  // 2 cm, 1 degree, x and y a little correlated
  covariance << 4e-4, 1e-4, 0.0, 1e-4, 4e-4, 0.0, 0.0, 0.0, 3e-4;
  map.anchor_covariance = covariance;
  map.grid = PatternGrid(width, height, core::Pose2(-1.5, -2.0, 0.0));
  map.start_s = 1700000000.5;
  map.end_s = 1700000012.25;
  return map;
}

std::vector<std::string> TempMapMessages(const core::TempMap& map) {
  std::vector<std::string> out;
  for (const core::TempMapTile& t : core::SplitTempMap(map)) {
    out.push_back(EncodeLcm(lcmtypes::ToMessage(t, kUtime)));
  }
  return out;
}

std::vector<std::string> KeyframeMessages(const core::OccupancyGrid& grid, int32_t version) {
  const std::vector<core::EncodedTile> tiles = core::EncodeAllTiles(grid);
  std::vector<std::string> out;
  for (size_t i = 0; i < tiles.size(); ++i) {
    const core::KeyframeTile k{version,       grid.geometry(),       64,
                               int32_t(i),    int32_t(tiles.size()), tiles[i].index,
                               tiles[i].frame};
    out.push_back(EncodeLcm(lcmtypes::ToMessage(k, kUtime)));
  }
  return out;
}

std::vector<std::string> DeltaMessages(const core::OccupancyGrid& before,
                                       const core::OccupancyGrid& after, int32_t base_version,
                                       const core::TileOptions& options = {}) {
  const std::vector<core::EncodedTile> tiles = core::EncodeChangedTiles(before, after, options);
  std::vector<std::string> out;
  for (size_t i = 0; i < tiles.size(); ++i) {
    const core::DeltaTile d{base_version, int32_t(i), int32_t(tiles.size()), tiles[i].index,
                            tiles[i].frame};
    out.push_back(EncodeLcm(lcmtypes::ToMessage(d, kUtime)));
  }
  if (tiles.empty()) {  // a version that changed no cell travels as one empty delta
    out.push_back(EncodeLcm(lcmtypes::ToMessage(core::DeltaTile{base_version, 0, 0, {}, {}}, 0)));
  }
  return out;
}

std::string Join(const std::vector<std::string>& parts) {
  std::string out;
  for (const std::string& p : parts) out += p;
  return out;
}

// The current map the delta targets seed their replica with: 100 x 70 cells, 2 x 2 tiles.
core::OccupancyGrid MapV0() { return core::OccupancyGrid(core::GridGeometry(0.05, 100, 70)); }
core::OccupancyGrid WithBox(core::OccupancyGrid grid, int x0, int y0, int w, int h,
                            core::CellState state) {
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x) grid.SetState({x, y}, state);
  return grid;
}

void AddTempMaps(SeedCorpus& corpus) {
  const std::vector<std::string> big = TempMapMessages(SampleTempMap(100, 80, 7));
  const std::vector<std::string> small = TempMapMessages(SampleTempMap(40, 30, 8));
  for (size_t i = 0; i < big.size(); ++i) {
    corpus.Add("lcm_tempmap_tile", "tile" + std::to_string(i) + "_of_4", big[i]);
  }
  corpus.Add("lcm_tempmap_tile", "single_tile_map", small[0]);
  corpus.Add("temp_map_assembler", "four_tiles", Join(big));
  corpus.Add("temp_map_assembler", "interleaved_two_maps",
             big[0] + small[0] + big[2] + big[1] + big[0] + big[3]);
}

void AddCurrentMaps(SeedCorpus& corpus) {
  const core::OccupancyGrid v0 = MapV0();
  const core::OccupancyGrid v1 = WithBox(v0, 10, 10, 12, 8, core::CellState::kOccupied);
  const core::OccupancyGrid v2 = WithBox(v1, 70, 60, 20, 10, core::CellState::kFree);
  const std::vector<std::string> keyframe = KeyframeMessages(v1, 1);
  for (size_t i = 0; i < keyframe.size(); ++i) {
    corpus.Add("lcm_map_keyframe", "v1_tile" + std::to_string(i), keyframe[i]);
  }
  corpus.Add("lcm_map_keyframe", "single_tile_map", KeyframeMessages(PatternGrid(60, 40), 3)[0]);
  const std::vector<std::string> d01 = DeltaMessages(v0, v1, 0), d12 = DeltaMessages(v1, v2, 1);
  corpus.Add("lcm_map_delta", "box_added", d01[0]);
  corpus.Add("lcm_map_delta", "edge_tile_cleared", d12[0]);
  corpus.Add("lcm_map_delta", "nothing_changed", DeltaMessages(v1, v1, 4)[0]);
  core::TileOptions zlib;
  zlib.codec.compression = core::Compression::kZlib;
  corpus.Add("lcm_map_delta", "zlib", DeltaMessages(v0, v1, 0, zlib)[0]);
  corpus.Add("map_replica", "keyframe_then_deltas", Join(keyframe) + Join(d12));
  corpus.Add("map_replica", "deltas_from_the_static_map", Join(d01) + Join(d12));
  corpus.Add("map_replica", "delta_before_its_keyframe", Join(d12) + Join(keyframe));
}

void AddCodecFrames(SeedCorpus& corpus) {
  const core::OccupancyGrid grid = PatternGrid(100, 80);
  for (const auto packing : {core::CellPacking::kTriState2Bit, core::CellPacking::kTriState8Bit,
                             core::CellPacking::kLogOddsInt8}) {
    for (const auto compression :
         {core::Compression::kNone, core::Compression::kZstd, core::Compression::kZlib}) {
      core::CodecOptions options;
      options.packing = packing;
      options.compression = compression;
      corpus.Add(
          "map_codec",
          std::string(core::CellPackingName(packing)) + "_" + core::CompressionName(compression),
          core::EncodeWindow(grid, {0, 0, 100, 80}, options));
    }
  }
  corpus.Add("map_codec", "window_64_16", core::EncodeWindow(grid, {64, 16, 30, 20}));
  const core::OccupancyGrid before = PatternGrid(50, 40);
  const core::OccupancyGrid after = WithBox(before, 5, 5, 30, 20, core::CellState::kOccupied);
  for (const int tile_size : {16, 32}) {
    core::TileOptions options;
    options.tile_size_cells = tile_size;
    corpus.Add("tile_delta", "delta_tiles_" + std::to_string(tile_size),
               WriteTileList(tile_size, 50, 40, core::EncodeChangedTiles(before, after, options)));
  }
  corpus.Add("tile_delta", "keyframe_tiles_64",
             WriteTileList(64, 100, 80, core::EncodeAllTiles(grid)));
}

}  // namespace

void AddTransportSeeds(SeedCorpus& corpus) {
  AddTempMaps(corpus);
  AddCurrentMaps(corpus);
  AddCodecFrames(corpus);
  corpus.Add("temp_map_file", "map_100x80", core::EncodeTempMap(SampleTempMap(100, 80, 7)));
  corpus.Add("temp_map_file", "map_40x30", core::EncodeTempMap(SampleTempMap(40, 30, 8)));
}

}  // namespace fleetmap::fuzz
