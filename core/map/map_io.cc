#include "core/map/map_io.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/io/file_io.h"
#include "core/map/image_file.h"
#include "core/map/map_yaml.h"

namespace fleetmap::core {

// Weak: null unless the program links fleetmap_core_image (core/map/image_file.h says why).
Result<DecodedImage> DecodeImageFile(const std::string& path) __attribute__((weak));

namespace {

namespace fs = std::filesystem;

constexpr int64_t kMaxYamlBytes = 1 << 20;  // a map YAML is a few hundred bytes
constexpr uint8_t kTrinaryOccupiedGrey = 0;
constexpr uint8_t kTrinaryFreeGrey = 254;
constexpr uint8_t kTrinaryUnknownGrey = 205;
constexpr uint8_t kRawUnknownGrey = 255;  // what ROS 1 map_server reads as -1

// ---- Pixels to cells (map_server's rules, see the header) ----

float LogOddsOf(double p, const LogOddsLimits& limits) {
  if (p <= 0.0) return limits.min_log_odds;
  if (p >= 1.0) return limits.max_log_odds;
  return ProbabilityToLogOdds(p);  // the grid clamps
}

// `shade`: mean of the pixel's channels, 0..255, before negate.
float PixelLogOdds(double shade, bool opaque, const MapMetadata& m, const OccupancyGrid& grid) {
  if (m.negate) shade = 255.0 - shade;
  if (m.mode == MapMode::kRaw) {
    const double percent = std::round(shade);
    return percent <= 100.0 ? LogOddsOf(percent / 100.0, grid.limits()) : 0.0f;
  }
  if (m.mode == MapMode::kScale && !opaque) return grid.CanonicalLogOdds(CellState::kUnknown);
  const double p = (255.0 - shade) / 255.0;
  if (p > m.thresholds.occupied_probability) return grid.CanonicalLogOdds(CellState::kOccupied);
  if (p < m.thresholds.free_probability) return grid.CanonicalLogOdds(CellState::kFree);
  if (m.mode == MapMode::kTrinary) return grid.CanonicalLogOdds(CellState::kUnknown);
  return LogOddsOf(p, grid.limits());
}

Result<OccupancyGrid> MakeGrid(const MapMetadata& m, int width, int height,
                               const LogOddsLimits& limits) {
  const GridGeometry geometry(m.resolution_m, width, height, m.origin);
  FLEETMAP_RETURN_IF_ERROR(geometry.Validate());
  FLEETMAP_RETURN_IF_ERROR(limits.Validate());
  return OccupancyGrid(geometry, limits);
}

// Image row 0 is the top of the map, grid row 0 its bottom.
void SetPixel(OccupancyGrid& grid, int x, int image_row, float log_odds) {
  grid.SetLogOdds({x, grid.geometry().height() - 1 - image_row}, log_odds);
}

Result<OccupancyGrid> GridFromGray(const GrayImage& image, const MapMetadata& m,
                                   const LogOddsLimits& limits) {
  Result<OccupancyGrid> grid = MakeGrid(m, image.width, image.height, limits);
  if (!grid.ok()) return grid;
  std::array<float, 256> table{};
  for (int v = 0; v < 256; ++v) table[v] = PixelLogOdds(v, true, m, *grid);
  for (int row = 0; row < image.height; ++row) {
    for (int x = 0; x < image.width; ++x) SetPixel(*grid, x, row, table[image.at(x, row)]);
  }
  return grid;
}

// ---- Images read by OpenCV ----

uint32_t BigEndian32(const unsigned char* p) {
  return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | p[3];
}

// Refuses a PNG whose header announces an absurd size, before OpenCV allocates it.
Status CheckPngSize(const std::string& path) {
  unsigned char h[24] = {};
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(h), sizeof(h));
  if (in.gcount() != sizeof(h) || std::memcmp(h, "\x89PNG\r\n\x1a\n", 8) != 0 ||
      std::memcmp(h + 12, "IHDR", 4) != 0) {
    return OkStatus();  // not a PNG: OpenCV decides
  }
  const uint64_t width = BigEndian32(h + 16), height = BigEndian32(h + 20);
  if (width * height > static_cast<uint64_t>(kMaxGridCells)) {
    return OutOfRange(path + ": PNG image of " + std::to_string(width) + " x " +
                      std::to_string(height) + " pixels exceeds the limit of " +
                      std::to_string(kMaxGridCells) + " pixels");
  }
  return OkStatus();
}

// map_server's shade: the mean of the colour channels, alpha averaged in only in trinary mode.
double ChannelMean(const uint8_t* px, int channels, MapMode mode) {
  if (channels == 1) return px[0];
  const int averaged = channels == 4 && mode == MapMode::kTrinary ? 4 : 3;
  int sum = 0;
  for (int c = 0; c < averaged; ++c) sum += px[c];
  return static_cast<double>(sum) / averaged;
}

Result<OccupancyGrid> GridFromImageFile(const MapMetadata& m, const LogOddsLimits& limits) {
  if (DecodeImageFile == nullptr) {
    return Unimplemented(m.image_path +
                         ": this program reads PGM map images only (other formats need "
                         "fleetmap_core_image, left out to keep it small): convert the image "
                         "to PGM, e.g. with fleetmap-maptool");
  }
  FLEETMAP_RETURN_IF_ERROR(CheckPngSize(m.image_path));
  Result<DecodedImage> image = DecodeImageFile(m.image_path);
  if (!image.ok()) return image.status();
  Result<OccupancyGrid> grid = MakeGrid(m, image->width, image->height, limits);
  if (!grid.ok()) return grid;
  const int channels = image->channels;
  const uint8_t* px = image->pixels.data();
  for (int row = 0; row < image->height; ++row) {
    for (int x = 0; x < image->width; ++x, px += channels) {
      const bool opaque = channels != 4 || px[3] == 255;
      SetPixel(*grid, x, row, PixelLogOdds(ChannelMean(px, channels, m.mode), opaque, m, *grid));
    }
  }
  return grid;
}

bool IsPgmPath(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext == ".pgm";
}

// ---- Cells to pixels ----

CellState StateOfGrey(int grey, const OccupancyThresholds& t) {
  const double p = (255.0 - grey) / 255.0;
  if (p > t.occupied_probability) return CellState::kOccupied;
  if (p < t.free_probability) return CellState::kFree;
  return CellState::kUnknown;
}

// 255 (1 - p), moved towards the side of `state` until it loads with that state.
// The probability of a stored cell; a NaN (a broken grid invariant) counts as unknown.
double CellProbability(float log_odds) {
  const double p = LogOddsToProbability(log_odds);
  return std::isnan(p) ? 0.5 : p;
}

uint8_t ScaleGrey(float log_odds, CellState state, const OccupancyThresholds& t) {
  int grey = static_cast<int>(std::lround(255.0 * (1.0 - CellProbability(log_odds))));
  // Ends within 255 steps: grey 0 loads occupied, 255 free, and validated thresholds leave a
  // grey between them.
  for (CellState s = StateOfGrey(grey, t); s != state && grey >= 0 && grey <= 255;
       s = StateOfGrey(grey, t)) {
    const bool darker =
        state == CellState::kOccupied || (state == CellState::kUnknown && s == CellState::kFree);
    grey += darker ? -1 : 1;
  }
  return static_cast<uint8_t>(std::clamp(grey, 0, 255));
}

uint8_t RawGrey(float log_odds) {
  if (log_odds == 0.0f || std::isnan(log_odds)) return kRawUnknownGrey;
  return static_cast<uint8_t>(std::lround(100.0 * CellProbability(log_odds)));
}

uint8_t TrinaryGrey(CellState state) {
  switch (state) {
    case CellState::kOccupied:
      return kTrinaryOccupiedGrey;
    case CellState::kFree:
      return kTrinaryFreeGrey;
    case CellState::kUnknown:
      break;
  }
  return kTrinaryUnknownGrey;
}

GrayImage GridToImage(const OccupancyGrid& grid, const MapSaveOptions& options) {
  const GridGeometry& g = grid.geometry();
  GrayImage image{g.width(), g.height(), std::vector<uint8_t>(static_cast<size_t>(g.num_cells()))};
  const TriStateClassifier classify(options.thresholds);
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      const float l = grid.log_odds({x, y});
      uint8_t grey = kTrinaryUnknownGrey;
      switch (options.mode) {
        case MapMode::kTrinary:
          grey = TrinaryGrey(classify(l));
          break;
        case MapMode::kScale:
          grey = ScaleGrey(l, classify(l), options.thresholds);
          break;
        case MapMode::kRaw:
          grey = RawGrey(l);
          break;
      }
      image.set(x, g.height() - 1 - y, grey);
    }
  }
  return image;
}

}  // namespace

Result<LoadedMap> LoadMapServerMap(const std::string& yaml_path, const MapLoadOptions& options) {
  Result<std::string> text = ReadFileBytes(yaml_path, kMaxYamlBytes);
  if (!text.ok()) return text.status();
  Result<MapMetadata> m = ParseMapYaml(*text, yaml_path);
  if (!m.ok()) return m.status();
  std::error_code ec;
  if (!fs::exists(m->image_path, ec)) {
    return NotFound(yaml_path + ": key 'image': image file '" + m->image_path + "' does not exist");
  }
  Result<OccupancyGrid> grid = InvalidArgument("unread");
  if (IsPgmPath(m->image_path)) {
    Result<GrayImage> image = ReadPgmFile(m->image_path, options.pgm);
    grid = image.ok() ? GridFromGray(*image, *m, options.limits) : image.status();
  } else {
    grid = GridFromImageFile(*m, options.limits);
  }
  if (!grid.ok()) return grid.status().WithContext(yaml_path);
  return LoadedMap{std::move(*grid), std::move(*m)};
}

Status MapSaveOptions::Validate() const {
  if (Status s = thresholds.Validate(); !s.ok()) return s.WithContext("MapSaveOptions.thresholds");
  if (mode == MapMode::kScale &&
      thresholds.occupied_probability - thresholds.free_probability < 2.0 / 255.0) {
    return InvalidArgument(
        "MapSaveOptions.thresholds: scale mode needs occupied_probability - free_probability "
        ">= 2/255");
  }
  return OkStatus();
}

Status SaveMapServerMap(const OccupancyGrid& grid, const std::string& yaml_path,
                        const MapSaveOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate().WithContext(yaml_path));
  const fs::path yaml(yaml_path);
  if (yaml.filename().empty()) return InvalidArgument(yaml_path + ": not a file name");
  const fs::path image = yaml.parent_path() / (yaml.stem().string() + ".pgm");
  if (image == yaml) return InvalidArgument(yaml_path + ": the YAML file must not end in .pgm");
  Result<std::string> text =
      MapYamlText(grid.geometry(), image.filename().string(), options.mode, options.thresholds);
  if (!text.ok()) return text.status().WithContext(yaml_path);
  FLEETMAP_RETURN_IF_ERROR(
      WritePgmFile(GridToImage(grid, options), image.string(), options.pgm_format));
  return WriteFileAtomically(yaml_path, *text);
}

}  // namespace fleetmap::core
