#include "core/image/map_render.h"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "core/io/file_io.h"
#include "core/map/image_file.h"
#include "core/map/pgm.h"

namespace fleetmap::core {
namespace {

constexpr int kMaxScalePixelsPerCell = 64;

Bgr CellColor(CellState state, const RenderOptions& options) {
  switch (state) {
    case CellState::kOccupied:
      return options.occupied_color;
    case CellState::kFree:
      return options.free_color;
    case CellState::kUnknown:
      break;
  }
  return options.unknown_color;
}

// Fills the scale x scale block of one cell; grid row y is picture row block height - 1 - y.
void PaintCell(BgrImage& image, const CellIndex& c, int grid_height, int scale, Bgr color) {
  const int row0 = (grid_height - 1 - c.y) * scale;
  const int col0 = c.x * scale;
  for (int row = row0; row < row0 + scale; ++row) {
    for (int col = col0; col < col0 + scale; ++col) image.set(col, row, color);
  }
}

}  // namespace

Status RenderOptions::Validate() const {
  if (scale_pixels_per_cell < 1 || scale_pixels_per_cell > kMaxScalePixelsPerCell) {
    return InvalidArgument("RenderOptions.scale_pixels_per_cell must be 1.." +
                           std::to_string(kMaxScalePixelsPerCell) + ", got " +
                           std::to_string(scale_pixels_per_cell));
  }
  return thresholds.Validate().WithContext("RenderOptions.thresholds");
}

Result<BgrImage> RenderGrid(const OccupancyGrid& grid, const RenderOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  const GridGeometry& g = grid.geometry();
  const int scale = options.scale_pixels_per_cell;
  const int64_t pixels = g.num_cells() * scale * scale;
  if (pixels > kMaxGridCells) {
    return OutOfRange("a picture of " + std::to_string(pixels) + " pixels exceeds the limit of " +
                      std::to_string(kMaxGridCells) + "; lower scale_pixels_per_cell");
  }
  BgrImage image{g.width() * scale, g.height() * scale,
                 std::vector<uint8_t>(static_cast<size_t>(pixels) * 3)};
  const TriStateClassifier classify(options.thresholds);
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      const Bgr color = CellColor(classify(grid.log_odds({x, y})), options);
      PaintCell(image, {x, y}, g.height(), scale, color);
    }
  }
  return image;
}

Status WritePng(const BgrImage& image, const std::string& path) {
  assert(image.pixels.size() == static_cast<size_t>(image.width) * image.height * 3);
  std::vector<uint8_t> png;
  try {
    // cv::Mat needs a non-const pointer but only reads here.
    const cv::Mat mat(image.height, image.width, CV_8UC3,
                      const_cast<uint8_t*>(image.pixels.data()));
    if (!cv::imencode(".png", mat, png)) return IoError(path + ": OpenCV cannot encode PNG");
  } catch (const std::exception& e) {  // cv::Exception, std::bad_alloc
    return IoError(path + ": OpenCV cannot encode PNG: " + e.what());
  }
  return WriteFileAtomically(
      path, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
}

Status RenderGridToPng(const OccupancyGrid& grid, const std::string& path,
                       const RenderOptions& options) {
  Result<BgrImage> image = RenderGrid(grid, options);
  if (!image.ok()) return image.status().WithContext(path);
  return WritePng(*image, path);
}

Result<BgrImage> ReadBgrImage(const std::string& path) {
  cv::Mat mat;
  try {
    mat = cv::imread(path, cv::IMREAD_COLOR);
  } catch (const std::exception& e) {  // cv::Exception, std::bad_alloc
    return InvalidArgument(path + ": OpenCV cannot read the image: " + e.what());
  }
  if (mat.empty()) return NotFound(path + ": missing or not an image OpenCV can decode");
  if (int64_t{mat.cols} * mat.rows > kMaxGridCells) {
    return OutOfRange(path + ": image exceeds the limit of " + std::to_string(kMaxGridCells) +
                      " pixels");
  }
  BgrImage image{mat.cols, mat.rows, {}};
  image.pixels.reserve(static_cast<size_t>(mat.cols) * mat.rows * 3);
  for (int row = 0; row < mat.rows; ++row) {
    const uint8_t* p = mat.ptr<uint8_t>(row);
    image.pixels.insert(image.pixels.end(), p, p + static_cast<size_t>(mat.cols) * 3);
  }
  return image;
}

}  // namespace fleetmap::core

namespace fleetmap::core {

Result<DecodedImage> DecodeImageFile(const std::string& path) {
  cv::Mat mat;
  try {
    mat = cv::imread(path, cv::IMREAD_UNCHANGED);
  } catch (const std::exception& e) {  // cv::Exception, std::bad_alloc
    return InvalidArgument(path + ": OpenCV cannot read the image: " + e.what());
  }
  if (mat.empty()) return InvalidArgument(path + ": not an image OpenCV can decode");
  if (mat.depth() != CV_8U) return Unimplemented(path + ": only 8-bit images are supported");
  if (mat.channels() != 1 && mat.channels() != 3 && mat.channels() != 4) {
    return Unimplemented(path + ": images need 1, 3 or 4 channels, not " +
                         std::to_string(mat.channels()));
  }
  if (int64_t{mat.cols} * mat.rows > kMaxGridCells) {
    return OutOfRange(path + ": image exceeds the limit of " + std::to_string(kMaxGridCells) +
                      " pixels");
  }
  DecodedImage image{mat.cols, mat.rows, mat.channels(), {}};
  const size_t row_bytes = static_cast<size_t>(mat.cols) * mat.channels();
  image.pixels.reserve(row_bytes * mat.rows);
  for (int row = 0; row < mat.rows; ++row) {
    const uint8_t* p = mat.ptr<uint8_t>(row);
    image.pixels.insert(image.pixels.end(), p, p + row_bytes);
  }
  return image;
}

}  // namespace fleetmap::core
