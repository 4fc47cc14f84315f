#include "sim/livinglab_map.h"

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace fleetmap::sim {
namespace {

using core::CellIndex;
using core::CellState;

// Drawing happens in a cv::Mat of CellState values (row = cell y), then copied into the grid.
cv::Mat StateImage(const core::OccupancyGrid& grid) {
  const auto& g = grid.geometry();
  cv::Mat img(g.height(), g.width(), CV_8UC1);
  for (int y = 0; y < g.height(); ++y)
    for (int x = 0; x < g.width(); ++x) img.at<uint8_t>(y, x) = uint8_t(grid.state({x, y}));
  return img;
}

int CopyStates(const cv::Mat& img, core::OccupancyGrid& grid) {
  int changed = 0;
  for (int y = 0; y < img.rows; ++y) {
    for (int x = 0; x < img.cols; ++x) {
      const auto s = static_cast<CellState>(img.at<uint8_t>(y, x));
      if (grid.state({x, y}) != s) ++changed;
      grid.SetState({x, y}, s);
    }
  }
  return changed;
}

int Cells(double metres, double resolution_m) {
  return static_cast<int>(std::lround(metres / resolution_m));
}

// A solid obstacle as seen by SLAM: unknown inside, an occupied outline `edge` cells thick.
void DrawSolidRect(cv::Mat& img, cv::Rect r, int edge) {
  cv::rectangle(img, r, uint8_t(CellState::kUnknown), cv::FILLED);
  cv::rectangle(img, r, uint8_t(CellState::kOccupied), edge);
}

}  // namespace

core::OccupancyGrid MakeLivingLabMap(const LivingLabOptions& o) {
  const double res = o.resolution_m;
  core::OccupancyGrid grid(core::GridGeometry(res, Cells(o.length_m, res), Cells(o.width_m, res)));
  cv::Mat img(grid.geometry().height(), grid.geometry().width(), CV_8UC1,
              cv::Scalar(uint8_t(CellState::kFree)));
  const int wall = std::max(1, Cells(o.wall_thickness_m, res));
  cv::rectangle(img, cv::Rect(0, 0, img.cols, img.rows), uint8_t(CellState::kOccupied), wall);
  // Fixed installations: one at the left end, one at the right end (the paper's Fig. 5a).
  DrawSolidRect(img, cv::Rect(wall, Cells(5.0, res), Cells(3.0, res), Cells(6.0, res)), 2);
  DrawSolidRect(img,
                cv::Rect(img.cols - wall - Cells(4.0, res), Cells(9.0, res), Cells(4.0, res),
                         Cells(7.0, res)),
                2);
  // Picking stations: ellipses on the centre line, 3 m x 1.6 m.
  for (int i = 0; i < o.picking_stations; ++i) {
    const double x = o.length_m * (i + 1) / (o.picking_stations + 1);
    const cv::Point c(Cells(x, res), Cells(o.width_m * 0.55, res));
    const cv::Size axes(Cells(1.5, res), Cells(0.8, res));
    cv::ellipse(img, c, axes, 0, 0, 360, uint8_t(CellState::kUnknown), cv::FILLED);
    cv::ellipse(img, c, axes, 0, 0, 360, uint8_t(CellState::kOccupied), 2);
  }
  // A rack along the top wall, with a gap, as halls have.
  DrawSolidRect(img,
                cv::Rect(Cells(12.0, res), img.rows - wall - Cells(1.2, res), Cells(14.0, res),
                         Cells(1.2, res)),
                2);
  DrawSolidRect(img,
                cv::Rect(Cells(30.0, res), img.rows - wall - Cells(1.2, res), Cells(14.0, res),
                         Cells(1.2, res)),
                2);
  CopyStates(img, grid);
  return grid;
}

int AddPalletToMap(core::OccupancyGrid& grid, double x_m, double y_m, double size_x_m,
                   double size_y_m) {
  const auto& g = grid.geometry();
  cv::Mat img = StateImage(grid);
  const core::CellIndex lo = g.WorldToCell({x_m - size_x_m / 2, y_m - size_y_m / 2});
  const core::CellIndex hi = g.WorldToCell({x_m + size_x_m / 2, y_m + size_y_m / 2});
  DrawSolidRect(img, cv::Rect(cv::Point(lo.x, lo.y), cv::Point(hi.x, hi.y)), 2);
  return CopyStates(img, grid);
}

}  // namespace fleetmap::sim
