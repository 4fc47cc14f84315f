#include "aggregator/alignment/surface_image.h"

#include <algorithm>

namespace fleetmap::aggregator {

int64_t BinaryImage::Count() const {
  return std::count_if(pixels.begin(), pixels.end(), [](uint8_t p) { return p != 0; });
}

BinaryImage CellsAtLeast(const core::OccupancyGrid& grid, float min_log_odds) {
  BinaryImage image{grid.geometry().width(), grid.geometry().height(), {}};
  image.pixels.resize(grid.cells().size());
  for (size_t i = 0; i < grid.cells().size(); ++i)
    image.pixels[i] = grid.cells()[i] >= min_log_odds;
  return image;
}

BinaryImage SurfaceCells(const core::OccupancyGrid& grid,
                         const core::OccupancyThresholds& thresholds) {
  const core::TriStateClassifier classify(thresholds);
  const int w = grid.geometry().width(), h = grid.geometry().height();
  const std::vector<float>& cells = grid.cells();
  auto is_free = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < w && y < h &&
           classify(cells[static_cast<size_t>(y) * w + x]) == core::CellState::kFree;
  };
  BinaryImage image{w, h, std::vector<uint8_t>(cells.size(), 0)};
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      if (classify(cells[i]) != core::CellState::kOccupied) continue;
      image.pixels[i] =
          is_free(x - 1, y) || is_free(x + 1, y) || is_free(x, y - 1) || is_free(x, y + 1);
    }
  }
  return image;
}

}  // namespace fleetmap::aggregator
