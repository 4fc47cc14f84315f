#include "aggregator/alignment/static_features.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

namespace fleetmap::aggregator {
namespace {

// The field on nodes every half cell: node (u, v) lies at cell coordinates (u / 2, v / 2),
// so cell centres and cell faces are both nodes. Each surface cell marks its centre, the
// nodes towards its surface neighbours and the faces it shares with free cells, so along a
// wall the field is flat from the surface row's centre line to its face, and its ridge lies
// a quarter cell in front of the centre (StaticFeatureOptions::surface_shift_cells).
core::Result<std::vector<float>> SurfaceDistanceField(const core::OccupancyGrid& map,
                                                      const BinaryImage& surface,
                                                      const core::OccupancyThresholds& t,
                                                      double sigma_cells) {
  const int nw = 2 * surface.width + 1, nh = 2 * surface.height + 1;
  const core::TriStateClassifier classify(t);
  auto is_free = [&](int x, int y) {
    return surface.Contains(x, y) &&
           classify(map.cells()[static_cast<size_t>(y) * surface.width + x]) ==
               core::CellState::kFree;
  };
  std::vector<float> field(static_cast<size_t>(nw) * nh, 0.0f);
  try {
    cv::Mat not_surface(nh, nw, CV_8UC1, cv::Scalar(255));
    auto mark = [&](int u, int v) {
      if (u >= 0 && v >= 0 && u < nw && v < nh) not_surface.at<uint8_t>(v, u) = 0;
    };
    static const int kSteps[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (int y = 0; y < surface.height; ++y) {  // the centre of cell (x, y) is node (2x+1, 2y+1)
      for (int x = 0; x < surface.width; ++x) {
        if (!surface.at(x, y)) continue;
        const int u = 2 * x + 1, v = 2 * y + 1;
        mark(u, v);
        for (const auto& s : kSteps) {
          const int nx = x + s[0], ny = y + s[1];
          if (surface.Contains(nx, ny) && surface.at(nx, ny)) mark(u + s[0], v + s[1]);
          if (!is_free(nx, ny)) continue;
          // The whole face towards free space: its middle and both corners.
          mark(u + s[0], v + s[1]);
          mark(u + s[0] + s[1], v + s[1] + s[0]);
          mark(u + s[0] - s[1], v + s[1] - s[0]);
        }
      }
    }
    cv::Mat distance(nh, nw, CV_32FC1, field.data());
    cv::distanceTransform(not_surface, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  } catch (const cv::Exception& e) {
    return core::InvalidArgument(std::string("static features: OpenCV failed: ") + e.what());
  }
  const double k = -0.5 / (sigma_cells * sigma_cells);
  for (float& d : field) {
    const double cells = 0.5 * double(d);  // node spacing is half a cell
    d = static_cast<float>(std::exp(k * cells * cells));
  }
  return field;
}

std::vector<uint8_t> OccupiedMask(const core::OccupancyGrid& grid,
                                  const core::OccupancyThresholds& thresholds) {
  const core::TriStateClassifier classify(thresholds);
  std::vector<uint8_t> mask(grid.cells().size());
  for (size_t i = 0; i < mask.size(); ++i)
    mask[i] = classify(grid.cells()[i]) == core::CellState::kOccupied;
  return mask;
}

// Moves each oriented line by surface_shift_cells towards its free side (its left).
std::vector<LineSegment> ShiftTowardsFree(std::vector<LineSegment> lines,
                                          const core::GridGeometry& g,
                                          const StaticFeatureOptions& o) {
  for (LineSegment& l : lines) {
    if (!l.oriented) continue;
    const Eigen::Vector2d d = l.direction();
    const Eigen::Vector2d shift =
        o.surface_shift_cells * g.resolution_m() * Eigen::Vector2d(-d.y(), d.x());
    l.a += shift;
    l.b += shift;
  }
  return lines;
}

}  // namespace

core::Status StaticFeatureOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(lines.Validate());
  FLEETMAP_RETURN_IF_ERROR(directions.Validate());
  if (!(field_sigma_cells > 0)) return core::InvalidArgument("field_sigma_cells must be > 0");
  if (!(surface_shift_cells >= 0 && surface_shift_cells <= 0.5))
    return core::InvalidArgument("surface_shift_cells must be in [0, 0.5]");
  return core::OkStatus();
}

core::Result<StaticMapFeatures> StaticMapFeatures::Compute(const core::OccupancyGrid& static_map,
                                                           const StaticFeatureOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  FLEETMAP_RETURN_IF_ERROR(static_map.geometry().Validate().WithContext("static map"));
  StaticMapFeatures f;
  f.geometry_ = static_map.geometry();
  LineFeatures features;
  FLEETMAP_ASSIGN_OR_RETURN(features, ExtractLineFeatures(static_map, options.lines));
  f.lines_ = std::move(features.lines);
  f.raw_segments_ = features.raw_segments;
  f.directions_ = FindDominantDirections(f.lines_, options.directions);
  f.lines_ = ShiftTowardsFree(f.lines_, f.geometry_, options);
  FLEETMAP_ASSIGN_OR_RETURN(
      f.field_, SurfaceDistanceField(static_map, features.edges, options.lines.thresholds,
                                     options.field_sigma_cells));
  f.occupied_ = OccupiedMask(static_map, options.lines.thresholds);
  const core::Pose2 to_grid = f.geometry_.origin().Inverse();
  const double scale = 1.0 / f.geometry_.resolution_m();
  f.to_grid_rotation_ = scale * Eigen::Rotation2Dd(to_grid.theta_rad).toRotationMatrix();
  f.to_grid_offset_ = scale * to_grid.translation();
  return f;
}

double StaticMapFeatures::SurfaceField(const Eigen::Vector2d& point_in_map) const {
  const Eigen::Vector2d n = 2.0 * GridPoint(point_in_map);  // node coordinates
  const double fx = std::floor(n.x()), fy = std::floor(n.y());
  const int x = static_cast<int>(fx), y = static_cast<int>(fy);
  const int nw = 2 * geometry_.width() + 1, nh = 2 * geometry_.height() + 1;
  if (x < 0 || y < 0 || x + 1 >= nw || y + 1 >= nh) return 0.0;
  const double ax = n.x() - fx, ay = n.y() - fy;
  const size_t i = static_cast<size_t>(y) * nw + x;
  const size_t up = i + static_cast<size_t>(nw);
  return (1 - ay) * ((1 - ax) * field_[i] + ax * field_[i + 1]) +
         ay * ((1 - ax) * field_[up] + ax * field_[up + 1]);
}

bool StaticMapFeatures::OnOccupied(const Eigen::Vector2d& point_in_map) const {
  const Eigen::Vector2d g = GridPoint(point_in_map);
  const core::CellIndex c{static_cast<int>(std::floor(g.x())), static_cast<int>(std::floor(g.y()))};
  return geometry_.Contains(c) && occupied_[geometry_.Index(c)] != 0;
}

}  // namespace fleetmap::aggregator
