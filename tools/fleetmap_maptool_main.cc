// fleetmap-maptool: small jobs on map_server maps from the command line. See --help.
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "core/codecs/map_render.h"
#include "core/map_io.h"
#include "core/number_text.h"
#include "core/tile_delta.h"
#include "core/version.h"
#include "tools/sim/livinglab_map.h"

namespace {

using namespace fleetmap;

constexpr const char* kUsage = R"(usage: fleetmap-maptool COMMAND ARGS

commands:
  livinglab OUT.yaml            write the default static map (the paper's 60 m x 18 m hall)
  info MAP.yaml                 print geometry and cell counts
  render MAP.yaml OUT.png [--scale N]
                                draw the map (free white, occupied black, unknown grey)
  codec MAP.yaml [--tile N] [--packing tristate2|tristate8|logodds8]
                 [--compression none|zstd|zlib] [--level L]
                                encode the map as tiles, decode it back, check it and
                                print the sizes and times
  diff BEFORE.yaml AFTER.yaml [--tile N]
                                size of the tile delta that turns BEFORE into AFTER
Exit status: 0 on success, 1 on a bad map or argument, 2 on usage errors.
)";

int Fail(const core::Status& s) {
  std::fprintf(stderr, "fleetmap-maptool: %s\n", s.ToString().c_str());
  return 1;
}

// The value after `flag` in args, or `fallback`.
std::string Flag(const std::vector<std::string>& args, const std::string& flag,
                 const std::string& fallback) {
  for (size_t i = 0; i + 1 < args.size(); ++i)
    if (args[i] == flag) return args[i + 1];
  return fallback;
}

core::Result<core::TileOptions> ParseTileOptions(const std::vector<std::string>& args) {
  core::TileOptions o;
  try {
    o.tile_size_cells = core::IntegerOrThrow(Flag(args, "--tile", "64"), "--tile");
    o.codec.level = core::IntegerOrThrow(Flag(args, "--level", "3"), "--level");
  } catch (const std::exception&) {
    return core::InvalidArgument("--tile and --level take whole numbers");
  }
  const std::string packing = Flag(args, "--packing", "tristate2");
  const std::string compression = Flag(args, "--compression", "zstd");
  bool found = false;
  for (auto p : {core::CellPacking::kTriState2Bit, core::CellPacking::kTriState8Bit,
                 core::CellPacking::kLogOddsInt8}) {
    if (packing == core::CellPackingName(p)) o.codec.packing = p, found = true;
  }
  if (!found) return core::InvalidArgument("unknown --packing '" + packing + "'");
  found = false;
  for (auto c : {core::Compression::kNone, core::Compression::kZstd, core::Compression::kZlib}) {
    if (compression == core::CompressionName(c)) o.codec.compression = c, found = true;
  }
  if (!found) return core::InvalidArgument("unknown --compression '" + compression + "'");
  FLEETMAP_RETURN_IF_ERROR(o.Validate());
  return o;
}

int Info(const std::string& path) {
  auto map = core::LoadMapServerMap(path);
  if (!map.ok()) return Fail(map.status());
  const core::OccupancyGrid& g = map->grid;
  std::printf("map: %s\ngeometry: %s\nimage: %s\nmode: %s\n", path.c_str(),
              g.geometry().ToString().c_str(), map->metadata.image_path.c_str(),
              core::MapModeName(map->metadata.mode));
  std::printf("cells: %lld occupied, %lld free, %lld unknown\n",
              (long long)g.CountState(core::CellState::kOccupied),
              (long long)g.CountState(core::CellState::kFree),
              (long long)g.CountState(core::CellState::kUnknown));
  return 0;
}

int Codec(const std::string& path, const std::vector<std::string>& args) {
  auto map = core::LoadMapServerMap(path);
  if (!map.ok()) return Fail(map.status());
  auto options = ParseTileOptions(args);
  if (!options.ok()) return Fail(options.status());
  const auto start = std::chrono::steady_clock::now();
  const auto tiles = core::EncodeAllTiles(map->grid, *options);
  const auto encoded = std::chrono::steady_clock::now();
  core::OccupancyGrid copy(map->grid.geometry());
  const core::Status s = core::ApplyTiles(tiles, options->tile_size_cells, copy);
  const auto decoded = std::chrono::steady_clock::now();
  if (!s.ok()) return Fail(s);
  int64_t mismatches = 0;
  const core::TriStateClassifier classify(options->codec.thresholds);
  for (size_t i = 0; i < copy.cells().size(); ++i)
    mismatches += classify(copy.cells()[i]) != classify(map->grid.cells()[i]);
  using us = std::chrono::microseconds;
  std::printf("raw (1 byte per cell, as a ROS OccupancyGrid): %lld B\n",
              (long long)map->grid.geometry().num_cells());
  std::printf("keyframe: %zu tiles of %d cells, %zu B (%s, %s level %d)\n", tiles.size(),
              options->tile_size_cells, core::TotalFrameBytes(tiles),
              core::CellPackingName(options->codec.packing),
              core::CompressionName(options->codec.compression), options->codec.level);
  std::printf("encode %lld us, decode %lld us, cells differing after the round trip: %lld\n",
              (long long)std::chrono::duration_cast<us>(encoded - start).count(),
              (long long)std::chrono::duration_cast<us>(decoded - encoded).count(),
              (long long)mismatches);
  return mismatches == 0 ? 0 : 1;
}

int Diff(const std::string& a, const std::string& b, const std::vector<std::string>& args) {
  auto before = core::LoadMapServerMap(a);
  if (!before.ok()) return Fail(before.status());
  auto after = core::LoadMapServerMap(b);
  if (!after.ok()) return Fail(after.status());
  if (!(before->grid.geometry() == after->grid.geometry())) {
    return Fail(core::InvalidArgument("the two maps differ in geometry"));
  }
  auto options = ParseTileOptions(args);
  if (!options.ok()) return Fail(options.status());
  const auto delta = core::EncodeChangedTiles(before->grid, after->grid, *options);
  std::printf("delta: %zu tiles, %zu B\n", delta.size(), core::TotalFrameBytes(delta));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (fleetmap::core::PrintVersionIfAsked(argc, argv, "fleetmap-maptool")) return 0;
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h") {
    std::fputs(kUsage, args.empty() ? stderr : stdout);
    return args.empty() ? 2 : 0;
  }
  const std::string& cmd = args[0];
  if (cmd == "livinglab" && args.size() >= 2) {
    const core::Status s = core::SaveMapServerMap(sim::MakeLivingLabMap(), args[1]);
    if (!s.ok()) return Fail(s);
    std::printf("wrote %s\n", args[1].c_str());
    return 0;
  }
  if (cmd == "info" && args.size() >= 2) return Info(args[1]);
  if (cmd == "render" && args.size() >= 3) {
    auto map = core::LoadMapServerMap(args[1]);
    if (!map.ok()) return Fail(map.status());
    core::RenderOptions options;
    options.scale_pixels_per_cell = std::atoi(Flag(args, "--scale", "1").c_str());
    const core::Status s = core::RenderGridToPng(map->grid, args[2], options);
    if (!s.ok()) return Fail(s);
    std::printf("wrote %s\n", args[2].c_str());
    return 0;
  }
  if (cmd == "codec" && args.size() >= 2) return Codec(args[1], args);
  if (cmd == "diff" && args.size() >= 3) return Diff(args[1], args[2], args);
  std::fprintf(stderr, "fleetmap-maptool: unknown command or missing arguments\n%s", kUsage);
  return 2;
}
