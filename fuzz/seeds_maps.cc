// Seeds of the map file targets: crops of the shipped LivingLab map as PGM (binary and plain),
// maps written by SaveMapServerMap in every mode (YAML + PGM), and the shipped scenarios.
#include <unistd.h>

#include "core/io/file_io.h"
#include "core/map/map_io.h"
#include "fuzz/map_yaml_pgm_input.h"
#include "fuzz/seed_sources.h"

namespace fleetmap::fuzz {
namespace {

namespace fs = std::filesystem;

std::string ReadText(const fs::path& path) {
  auto bytes = core::ReadFileBytes(path.string(), 1 << 20);
  return bytes.ok() ? *bytes : std::string();
}

// A corner of the LivingLab map with walls, free and unknown cells (or a pattern without it).
core::GrayImage Crop(const SeedInputs& in, int width, int height) {
  core::GrayImage crop{width, height, std::vector<uint8_t>(size_t(width) * height, 205)};
  auto map = core::ReadPgmFile((in.source_dir / "sim/worlds/livinglab/livinglab.pgm").string());
  for (int row = 0; row < height; ++row) {
    for (int x = 0; x < width; ++x) {
      const bool inside = map.ok() && x < map->width && row < map->height;
      crop.set(x, row, inside ? map->at(x, row) : static_cast<uint8_t>((x * row) % 3 * 100));
    }
  }
  return crop;
}

void AddPgm(SeedCorpus& corpus, const core::GrayImage& image) {
  corpus.Add("pgm", "livinglab_corner_p5", core::EncodePgm(image, core::PgmFormat::kBinary));
  corpus.Add("pgm", "livinglab_corner_p2", core::EncodePgm(image, core::PgmFormat::kAscii));
  corpus.Add("pgm", "comments_maxval_15",
             "P2\n# made by hand\n3 2 # size\n15\n0 7 15\n15 # row\n7 0\n");
}

// SaveMapServerMap's own files, read back.
void AddSavedMaps(SeedCorpus& corpus, const core::GrayImage& image) {
  core::OccupancyGrid grid(core::GridGeometry(0.05, image.width, image.height, {1.5, -2, 0.1}));
  for (int row = 0; row < image.height; ++row) {
    for (int x = 0; x < image.width; ++x) {
      const float l = image.at(x, row) < 50 ? 4.6f : image.at(x, row) > 250 ? -4.6f : 0.0f;
      grid.SetLogOdds({x, image.height - 1 - row}, l + 0.3f * float(x % 3 == 0));
    }
  }
  const fs::path folder =
      fs::temp_directory_path() / ("fleetmap_fuzz_seeds." + std::to_string(getpid()));
  fs::create_directories(folder);
  for (const core::MapMode mode :
       {core::MapMode::kTrinary, core::MapMode::kScale, core::MapMode::kRaw}) {
    core::MapSaveOptions options;
    options.mode = mode;
    options.pgm_format =
        mode == core::MapMode::kRaw ? core::PgmFormat::kAscii : core::PgmFormat::kBinary;
    const fs::path yaml = folder / "map.yaml";
    if (!core::SaveMapServerMap(grid, yaml.string(), options).ok()) continue;
    corpus.Add("map_load", core::MapModeName(mode),
               WriteMapYamlPgm(ReadText(yaml), ReadText(folder / "map.pgm")));
  }
  std::error_code ec;
  fs::remove_all(folder, ec);
}

}  // namespace

void AddMapSeeds(SeedCorpus& corpus, const SeedInputs& in) {
  const core::GrayImage image = Crop(in, 48, 32);
  AddPgm(corpus, image);
  AddSavedMaps(corpus, image);
  // The shipped map's own YAML (negate, thresholds as a user writes them) with a crop.
  std::string yaml = ReadText(in.source_dir / "sim/worlds/livinglab/livinglab.yaml");
  if (const size_t at = yaml.find("livinglab.pgm"); at != std::string::npos) {
    yaml.replace(at, 13, "map.pgm");
    corpus.Add("map_load", "livinglab_yaml",
               WriteMapYamlPgm(yaml, core::EncodePgm(image, core::PgmFormat::kBinary)));
  }
  for (const char* scenario : {"addition", "removal", "fleet", "fleet_short"}) {
    const std::string text =
        ReadText(in.source_dir / "sim/worlds/livinglab" / (std::string(scenario) + ".yaml"));
    if (!text.empty()) corpus.Add("scenario", scenario, text);
  }
}

}  // namespace fleetmap::fuzz
