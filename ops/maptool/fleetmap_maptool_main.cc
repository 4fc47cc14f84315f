// fleetmap-maptool: small jobs on map_server maps from the command line. See --help.
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "core/codec/tile_delta.h"
#include "core/command_line.h"
#include "core/image/map_render.h"
#include "core/map/map_io.h"
#include "sim/livinglab_map.h"

namespace {

using namespace fleetmap;

int Fail(const core::Status& s) {
  std::fprintf(stderr, "fleetmap-maptool: %s\n", s.ToString().c_str());
  return 1;
}

// The tile codec as the flags name it.
struct TileFlags {
  int tile_size_cells = 64;
  std::string packing = "tristate2";
  std::string compression = "zstd";
  int level = 3;
};

core::Result<core::TileOptions> ParseTileOptions(const TileFlags& flags) {
  core::TileOptions o;
  o.tile_size_cells = flags.tile_size_cells;
  o.codec.level = flags.level;
  bool found = false;
  for (auto p : {core::CellPacking::kTriState2Bit, core::CellPacking::kTriState8Bit,
                 core::CellPacking::kLogOddsInt8}) {
    if (flags.packing == core::CellPackingName(p)) o.codec.packing = p, found = true;
  }
  if (!found) return core::InvalidArgument("unknown --packing '" + flags.packing + "'");
  found = false;
  for (auto c : {core::Compression::kNone, core::Compression::kZstd, core::Compression::kZlib}) {
    if (flags.compression == core::CompressionName(c)) o.codec.compression = c, found = true;
  }
  if (!found) return core::InvalidArgument("unknown --compression '" + flags.compression + "'");
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

int Codec(const std::string& path, const TileFlags& flags) {
  auto map = core::LoadMapServerMap(path);
  if (!map.ok()) return Fail(map.status());
  auto options = ParseTileOptions(flags);
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

int Diff(const std::string& a, const std::string& b, const TileFlags& flags) {
  auto before = core::LoadMapServerMap(a);
  if (!before.ok()) return Fail(before.status());
  auto after = core::LoadMapServerMap(b);
  if (!after.ok()) return Fail(after.status());
  if (!(before->grid.geometry() == after->grid.geometry())) {
    return Fail(core::InvalidArgument("the two maps differ in geometry"));
  }
  auto options = ParseTileOptions(flags);
  if (!options.ok()) return Fail(options.status());
  const auto delta = core::EncodeChangedTiles(before->grid, after->grid, *options);
  std::printf("delta: %zu tiles, %zu B\n", delta.size(), core::TotalFrameBytes(delta));
  return 0;
}

int Render(const std::string& path, const std::string& png, int scale) {
  auto map = core::LoadMapServerMap(path);
  if (!map.ok()) return Fail(map.status());
  core::RenderOptions options;
  options.scale_pixels_per_cell = scale;
  const core::Status s = core::RenderGridToPng(map->grid, png, options);
  if (!s.ok()) return Fail(s);
  std::printf("wrote %s\n", png.c_str());
  return 0;
}

int LivingLab(const std::string& out) {
  const core::Status s = core::SaveMapServerMap(sim::MakeLivingLabMap(), out);
  if (!s.ok()) return Fail(s);
  std::printf("wrote %s\n", out.c_str());
  return 0;
}

void AddTileFlags(CLI::App* command, TileFlags& flags, bool codec) {
  command->add_option("--tile", flags.tile_size_cells, "tile edge, cells")->capture_default_str();
  if (!codec) return;
  command->add_option("--packing", flags.packing, "tristate2, tristate8 or logodds8")
      ->capture_default_str();
  command->add_option("--compression", flags.compression, "none, zstd or zlib")
      ->capture_default_str();
  command->add_option("--level", flags.level, "compression level")->capture_default_str();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app(
      "Small jobs on map_server maps.\n"
      "Exit status: 0 on success, 1 on a bad map or argument, 2 on usage errors.",
      "fleetmap-maptool");
  core::AddVersionFlag(app);
  app.require_subcommand(1);
  std::string map, other, out;
  int scale = 1;
  TileFlags flags;
  CLI::App* livinglab = app.add_subcommand(
      "livinglab", "write the default static map (the paper's 60 m x 18 m hall)");
  livinglab->add_option("OUT.yaml", out, "the map to write")->required();
  CLI::App* info = app.add_subcommand("info", "print geometry and cell counts");
  info->add_option("MAP.yaml", map, "the map")->required();
  CLI::App* render =
      app.add_subcommand("render", "draw the map (free white, occupied black, unknown grey)");
  render->add_option("MAP.yaml", map, "the map")->required();
  render->add_option("OUT.png", out, "the picture to write")->required();
  render->add_option("--scale", scale, "pixels per cell")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  CLI::App* codec = app.add_subcommand(
      "codec", "encode the map as tiles, decode it back, check it and print the sizes and times");
  codec->add_option("MAP.yaml", map, "the map")->required();
  AddTileFlags(codec, flags, true);
  CLI::App* diff =
      app.add_subcommand("diff", "size of the tile delta that turns BEFORE into AFTER");
  diff->add_option("BEFORE.yaml", map, "the map before")->required();
  diff->add_option("AFTER.yaml", other, "the map after")->required();
  AddTileFlags(diff, flags, false);
  if (const auto exit_status = core::ParseCommandLine(app, argc, argv)) return *exit_status;
  if (livinglab->parsed()) return LivingLab(out);
  if (info->parsed()) return Info(map);
  if (render->parsed()) return Render(map, out, scale);
  if (codec->parsed()) return Codec(map, flags);
  return Diff(map, other, flags);
}
