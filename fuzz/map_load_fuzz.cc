// map_server maps (core/map/map_io.h): a YAML and its PGM image (map_yaml_pgm_input.h) written to a
// scratch folder and loaded with LoadMapServerMap, as every process loads the static map. Any
// YAML is parsed; the image is only loaded when the YAML names the scratch map.pgm, so that
// fuzzed paths never make the target read other files. A map that loads has the image's size,
// the YAML's resolution and only finite cells within the grid's limits.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/map/map_io.h"
#include "fuzz/fuzz_check.h"
#include "fuzz/map_yaml_pgm_input.h"

namespace fleetmap::fuzz {
namespace {

namespace fs = std::filesystem;

// A folder of this process's own, removed at exit (tmpfs when there is one: no disk writes).
const fs::path& ScratchFolder() {
  static const fs::path folder = [] {
    const fs::path base = fs::is_directory("/dev/shm") ? "/dev/shm" : fs::temp_directory_path();
    fs::path f = base / ("fleetmap_map_load_fuzz." + std::to_string(getpid()));
    fs::create_directories(f);
    std::atexit([] {
      std::error_code ec;
      fs::remove_all(ScratchFolder(), ec);
    });
    return f;
  }();
  return folder;
}

void WriteFile(const fs::path& path, std::string_view bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), bytes.size());
}

void CheckLoaded(const core::LoadedMap& map) {
  const core::GridGeometry& g = map.grid.geometry();
  FUZZ_REQUIRE(g.Validate().ok() && g.resolution_m() == map.metadata.resolution_m);
  const core::LogOddsLimits& limits = map.grid.limits();
  for (const float cell : map.grid.cells()) {
    FUZZ_REQUIRE(std::isfinite(cell) && cell >= limits.min_log_odds && cell <= limits.max_log_odds);
  }
}

}  // namespace
}  // namespace fleetmap::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap;
  namespace fs = std::filesystem;
  const fuzz::MapYamlPgmInput in = fuzz::ReadMapYamlPgm(data, size);
  const fs::path yaml_path = fuzz::ScratchFolder() / "map.yaml";
  const fs::path pgm_path = fuzz::ScratchFolder() / "map.pgm";
  core::Result<core::MapMetadata> metadata =
      core::ParseMapYaml(std::string(in.yaml), yaml_path.string());
  if (!metadata.ok() || fs::path(metadata->image_path).lexically_normal() != pgm_path) return 0;
  fuzz::WriteFile(yaml_path, in.yaml);
  fuzz::WriteFile(pgm_path, in.pgm);
  core::Result<core::LoadedMap> map = core::LoadMapServerMap(yaml_path.string());
  if (map.ok()) {
    fuzz::CheckLoaded(*map);
    auto image = core::DecodePgm(in.pgm);
    FUZZ_REQUIRE(image.ok() && image->width == map->grid.geometry().width() &&
                 image->height == map->grid.geometry().height());
  }
  return 0;
}
