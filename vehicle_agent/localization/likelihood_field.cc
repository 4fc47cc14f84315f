#include "vehicle_agent/localization/likelihood_field.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "vehicle_agent/option_check.h"

namespace fleetmap::vehicle_agent {
namespace {

// The occupied cells of a window and, among them, the surfaces a beam can end on (occupied,
// with a 4-neighbour on the grid that is not), row-major in the window.
struct Surfaces {
  std::vector<uint8_t> occupied;
  std::vector<uint8_t> surface;
};

Surfaces FindSurfaces(const core::OccupancyGrid& map, const core::CellWindow& window) {
  const core::TriStateClassifier classify;
  const core::GridGeometry& g = map.geometry();
  const int w = g.width(), h = g.height();
  // A surface depends on the cells around it: classify the window and a border of one.
  const core::CellWindow around = g.Grown(window, 1);
  std::vector<uint8_t> o(static_cast<size_t>(around.num_cells()));
  for (int y = 0; y < around.height; ++y)
    for (int x = 0; x < around.width; ++x)
      o[size_t(y) * around.width + x] =
          classify(map.cells()[size_t(y + around.y0) * w + (x + around.x0)]) ==
          core::CellState::kOccupied;
  const auto occupied = [&](int x, int y) {
    return o[size_t(y - around.y0) * around.width + (x - around.x0)] != 0;
  };
  Surfaces s;
  s.occupied.assign(static_cast<size_t>(window.num_cells()), 0);
  s.surface.assign(s.occupied.size(), 0);
  for (int y = window.y0; y < window.y0 + window.height; ++y) {
    for (int x = window.x0; x < window.x0 + window.width; ++x) {
      const size_t i = size_t(y - window.y0) * window.width + (x - window.x0);
      s.occupied[i] = occupied(x, y);
      s.surface[i] =
          s.occupied[i] && ((x > 0 && !occupied(x - 1, y)) || (x + 1 < w && !occupied(x + 1, y)) ||
                            (y > 0 && !occupied(x, y - 1)) || (y + 1 < h && !occupied(x, y + 1)));
    }
  }
  return s;
}

// Distance from every cell centre of a window to the nearest surface cell centre in it, in
// cells (very far everywhere should OpenCV refuse).
std::vector<float> DistanceToSurface(const core::CellWindow& window,
                                     const std::vector<uint8_t>& surface) {
  // distanceTransform measures the distance to the nearest zero pixel: zero = surface.
  cv::Mat not_surface(window.height, window.width, CV_8UC1);
  for (size_t i = 0; i < surface.size(); ++i) not_surface.data[i] = surface[i] ? 0 : 255;
  std::vector<float> distance(surface.size(), 1e9f);
  try {
    cv::Mat out(window.height, window.width, CV_32FC1, distance.data());
    cv::distanceTransform(not_surface, out, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  } catch (const cv::Exception&) {
    distance.assign(surface.size(), 1e9f);
  }
  return distance;
}

}  // namespace

core::Status LikelihoodFieldOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(CheckOption(z_hit >= 0, "LikelihoodFieldOptions.z_hit", z_hit, ">= 0"));
  FLEETMAP_RETURN_IF_ERROR(
      CheckOption(z_rand >= 0, "LikelihoodFieldOptions.z_rand", z_rand, ">= 0"));
  FLEETMAP_RETURN_IF_ERROR(CheckOption(z_hit + z_rand > 0 && std::isfinite(z_hit + z_rand),
                                       "LikelihoodFieldOptions.z_hit + z_rand", z_hit + z_rand,
                                       "> 0 and finite"));
  FLEETMAP_RETURN_IF_ERROR(CheckOption(sigma_hit_m > 0 && std::isfinite(sigma_hit_m),
                                       "LikelihoodFieldOptions.sigma_hit_m", sigma_hit_m, "> 0"));
  FLEETMAP_RETURN_IF_ERROR(CheckOption(max_distance_m > 0 && std::isfinite(max_distance_m),
                                       "LikelihoodFieldOptions.max_distance_m", max_distance_m,
                                       "> 0"));
  FLEETMAP_RETURN_IF_ERROR(
      CheckOption(beam_stride >= 1, "LikelihoodFieldOptions.beam_stride", beam_stride, ">= 1"));
  return CheckOption(max_range_m > 0 && std::isfinite(max_range_m),
                     "LikelihoodFieldOptions.max_range_m", max_range_m, "> 0 and finite");
}

LikelihoodField::LikelihoodField(const LikelihoodFieldOptions& options) : options_(options) {
  assert(options.Validate().ok());
  log_p_far_ = LogProbabilityOfDistance(options.max_distance_m);
}

double LikelihoodField::LogProbabilityOfDistance(double distance_m) const {
  const double sigma = options_.sigma_hit_m;
  const double u = distance_m / sigma;
  const double p = options_.z_hit * std::exp(-0.5 * u * u) / (sigma * std::sqrt(2.0 * M_PI)) +
                   options_.z_rand / options_.max_range_m;
  return std::log(std::max(p, kMinBeamLikelihood));
}

void LikelihoodField::SetMap(const core::OccupancyGrid& map) {
  geometry_ = map.geometry();
  distance_m_.clear();
  log_p_.clear();
  if (geometry_.num_cells() == 0) return;
  distance_m_.resize(static_cast<size_t>(geometry_.num_cells()));
  log_p_.resize(distance_m_.size());
  Recompute(map, geometry_.full_window());
}

void LikelihoodField::UpdateMap(const core::OccupancyGrid& map, const core::CellWindow& changed) {
  if (!has_map() || !(map.geometry() == geometry_)) return SetMap(map);
  // A cell further than the reach from every change keeps its value: the surfaces that
  // changed lie within a cell of the window, and from beyond the reach they are at the cap.
  const core::CellWindow affected = geometry_.Grown(changed, ReachCells());
  if (affected.num_cells() > 0) Recompute(map, affected);
}

int LikelihoodField::ReachCells() const {
  // A free cell's distance is its centre's to the nearest surface centre less half a cell:
  // beyond max_distance_m / resolution + 0.5 cells it is capped. One cell more for the
  // surfaces' own neighbourhood.
  return static_cast<int>(std::ceil(options_.max_distance_m / geometry_.resolution_m() + 0.5)) + 1;
}

void LikelihoodField::Recompute(const core::OccupancyGrid& map, const core::CellWindow& out) {
  // The nearest surface of a cell of `out` whose distance is below the cap lies within the
  // reach of it: the distance transform of that larger window gives the same values as the
  // whole map's.
  const core::CellWindow source = geometry_.Grown(out, ReachCells());
  const Surfaces surfaces = FindSurfaces(map, source);
  const std::vector<float> distance = DistanceToSurface(source, surfaces.surface);
  const double res = geometry_.resolution_m();
  for (int y = out.y0; y < out.y0 + out.height; ++y) {
    for (int x = out.x0; x < out.x0 + out.width; ++x) {
      const size_t local = size_t(y - source.y0) * source.width + (x - source.x0);
      const size_t i = size_t(y) * geometry_.width() + x;
      // The surface is the face between a surface cell and its free neighbour, half a cell
      // from either centre: both cells next to a face are 0.5 cells from it, on either side.
      const double cells =
          surfaces.occupied[local] ? distance[local] + 0.5 : std::max(0.0f, distance[local] - 0.5f);
      const double d = std::min(cells * res, options_.max_distance_m);
      distance_m_[i] = static_cast<float>(d);
      // Most cells of a large map lie beyond the cap: their value is the one computed once (an
      // exp and a log per cell were a tenth of a fine-resolution world's run).
      log_p_[i] = static_cast<float>(d >= options_.max_distance_m ? log_p_far_
                                                                  : LogProbabilityOfDistance(d));
    }
  }
}

double LikelihoodField::LogLikelihood(const std::vector<Eigen::Vector2f>& endpoints_in_base,
                                      const core::Pose2& base_in_map) const {
  if (log_p_.empty()) return 0.0;
  // Work in continuous cell coordinates of the grid frame.
  const core::Pose2 base_in_grid = geometry_.origin().Inverse() * base_in_map;
  const double inv_res = 1.0 / geometry_.resolution_m();
  const float c = static_cast<float>(std::cos(base_in_grid.theta_rad) * inv_res);
  const float s = static_cast<float>(std::sin(base_in_grid.theta_rad) * inv_res);
  const float px = static_cast<float>(base_in_grid.x_m * inv_res);
  const float py = static_cast<float>(base_in_grid.y_m * inv_res);
  const float w = static_cast<float>(geometry_.width()), h = static_cast<float>(geometry_.height());
  double sum = 0.0;
  for (const Eigen::Vector2f& e : endpoints_in_base) {
    const float gx = px + c * e.x() - s * e.y();
    const float gy = py + s * e.x() + c * e.y();
    if (gx >= 0.0f && gy >= 0.0f && gx < w && gy < h) {
      sum += log_p_[static_cast<size_t>(gy) * geometry_.width() + static_cast<size_t>(gx)];
    } else {
      sum += log_p_far_;
    }
  }
  return sum;
}

std::optional<size_t> LikelihoodField::CellOf(const Eigen::Vector2d& point_in_map) const {
  const Eigen::Vector2d g = geometry_.WorldToGrid(point_in_map);
  // Checked in floating point first: casting a huge or NaN coordinate is undefined.
  if (!(g.x() >= 0.0 && g.y() >= 0.0 && g.x() < geometry_.width() && g.y() < geometry_.height()))
    return std::nullopt;
  return static_cast<size_t>(g.y()) * geometry_.width() + static_cast<size_t>(g.x());
}

double LikelihoodField::LogLikelihoodAt(const Eigen::Vector2d& point_in_map) const {
  const auto cell = log_p_.empty() ? std::nullopt : CellOf(point_in_map);
  return cell ? log_p_[*cell] : log_p_far_;
}

double LikelihoodField::DistanceAt(const Eigen::Vector2d& point_in_map) const {
  const auto cell = distance_m_.empty() ? std::nullopt : CellOf(point_in_map);
  return cell ? distance_m_[*cell] : options_.max_distance_m;
}

ScanScore LikelihoodField::Score(const core::LaserScan& scan,
                                 const core::Pose2& scanner_in_map) const {
  if (log_p_.empty() || !scanner_in_map.IsFinite() || !scan.Validate().ok()) return {};
  const double z_max = std::min(options_.max_range_m, scan.range_max_m);
  ScanScoreAccumulator acc;
  for (size_t i = 0; i < scan.size(); i += static_cast<size_t>(options_.beam_stride)) {
    const BeamReading reading = ClassifyBeam(scan, i, z_max);
    if (reading != BeamReading::kReturn) {
      reading == BeamReading::kInvalid ? acc.CountInvalid() : acc.CountNoReturn();
      continue;  // table 6.3 skips max-range readings
    }
    const double a = scan.angle(i), r = scan.ranges_m[i];
    acc.AddLogBeam(LogLikelihoodAt(scanner_in_map.Apply({r * std::cos(a), r * std::sin(a)})));
  }
  return acc.Finish();
}

std::unique_ptr<ScanLikelihood> MakeLikelihoodField(const LikelihoodFieldOptions& options) {
  return std::make_unique<LikelihoodField>(options);
}

}  // namespace fleetmap::vehicle_agent
