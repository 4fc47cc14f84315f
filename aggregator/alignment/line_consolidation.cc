#include "aggregator/alignment/line_consolidation.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numeric>

namespace fleetmap::aggregator {
namespace {

struct Group {
  LineSegment line;  // the longest member's line, extended over every member
  double t_min = 0.0, t_max = 0.0;
};

// Whether `s` belongs to the edge of group `g`.
bool Joins(const Group& g, const LineSegment& s, const ConsolidationOptions& o) {
  const double angle =
      LineAngleDiff(LineDirectionAngle(g.line.direction()), LineDirectionAngle(s.direction()));
  if (std::abs(angle) > o.max_angle_diff_rad) return false;
  if (std::abs(g.line.SignedDistance(s.a)) > o.max_normal_distance_cells ||
      std::abs(g.line.SignedDistance(s.b)) > o.max_normal_distance_cells) {
    return false;
  }
  const double ta = g.line.Along(s.a), tb = g.line.Along(s.b);
  const double gap = std::max(std::min(ta, tb) - g.t_max, g.t_min - std::max(ta, tb));
  return gap <= o.max_gap_cells;
}

void Extend(Group& g, const LineSegment& s) {
  for (const Eigen::Vector2d& p : {s.a, s.b}) {
    g.t_min = std::min(g.t_min, g.line.Along(p));
    g.t_max = std::max(g.t_max, g.line.Along(p));
  }
}

// Centres of set pixels within `band` of the group's line and its extent. Walks the line
// along its major axis, so the cost is proportional to its length.
std::vector<Eigen::Vector2d> BandPoints(const Group& g, const BinaryImage& image, double band) {
  const Eigen::Vector2d d = g.line.direction();
  const Eigen::Vector2d p0 = g.line.a + (g.t_min - band) * d;
  const Eigen::Vector2d p1 = g.line.a + (g.t_max + band) * d;
  const bool along_x = std::abs(d.x()) >= std::abs(d.y());
  const int major = along_x ? 0 : 1;
  const double reach = band / std::max(std::abs(d[major]), 1e-9) + 1.0;
  std::vector<Eigen::Vector2d> pixels;
  const int lo = int(std::floor(std::min(p0[major], p1[major]))) - 1;
  const int hi = int(std::ceil(std::max(p0[major], p1[major]))) + 1;
  for (int m = lo; m <= hi; ++m) {
    // The minor coordinate of the line at this major pixel centre.
    const double t = (m + 0.5 - g.line.a[major]) / d[major];
    const double c = g.line.a[1 - major] + t * d[1 - major];
    for (int n = int(std::floor(c - reach)); n <= int(std::ceil(c + reach)); ++n) {
      const int x = along_x ? m : n, y = along_x ? n : m;
      if (!image.Contains(x, y) || !image.at(x, y)) continue;
      const Eigen::Vector2d p(x + 0.5, y + 0.5);
      const double along = g.line.Along(p);
      if (std::abs(g.line.SignedDistance(p)) <= band && along >= g.t_min - band &&
          along <= g.t_max + band) {
        pixels.push_back(p);
      }
    }
  }
  return pixels;
}

// Total least squares line through the pixels, clipped to their extent.
LineSegment Refit(const Group& g, const std::vector<Eigen::Vector2d>& pixels) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : pixels) mean += p;
  mean /= double(pixels.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& p : pixels) cov += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  Eigen::Vector2d d = eig.eigenvectors().col(1);  // largest eigenvalue: the direction
  if (d.dot(g.line.direction()) < 0) d = -d;
  double t0 = 1e300, t1 = -1e300;
  for (const auto& p : pixels) {
    t0 = std::min(t0, d.dot(p - mean));
    t1 = std::max(t1, d.dot(p - mean));
  }
  return {mean + t0 * d, mean + t1 * d};
}

// Two groups can refit to the same edge: a Hough segment that crosses a thick edge slantwise
// (more than max_angle_diff_rad off it) starts a group of its own, and its band then holds
// the same pixels. A refitted line that lies on a longer one, within its extent (and a cell),
// is that line again and is dropped; one that reaches beyond it stays (the chords of a curved
// wall overlap, and are not one straight line). `lines` longest first.
std::vector<LineSegment> WithoutDuplicates(const std::vector<LineSegment>& lines,
                                           const ConsolidationOptions& o) {
  std::vector<LineSegment> kept;
  for (const LineSegment& s : lines) {
    const bool again = std::any_of(kept.begin(), kept.end(), [&](const LineSegment& k) {
      const Group g{k, 0.0, k.length()};
      const double ta = k.Along(s.a), tb = k.Along(s.b);
      return Joins(g, s, o) && std::min(ta, tb) >= -1.0 && std::max(ta, tb) <= k.length() + 1.0;
    });
    if (!again) kept.push_back(s);
  }
  return kept;
}

}  // namespace

core::Status ConsolidationOptions::Validate() const {
  if (!(max_angle_diff_rad > 0 && max_angle_diff_rad < M_PI / 4))
    return core::InvalidArgument("consolidation.max_angle_diff_rad must be in (0, pi/4)");
  if (!(max_normal_distance_cells >= 0))
    return core::InvalidArgument("consolidation.max_normal_distance_cells must be >= 0");
  if (!(max_gap_cells >= 0))
    return core::InvalidArgument("consolidation.max_gap_cells must be >= 0");
  if (!(fit_band_cells > 0))
    return core::InvalidArgument("consolidation.fit_band_cells must be > 0");
  if (!(min_length_cells >= 0))
    return core::InvalidArgument("consolidation.min_length_cells must be >= 0");
  if (min_fit_pixels < 2) return core::InvalidArgument("consolidation.min_fit_pixels must be >= 2");
  return core::OkStatus();
}

std::vector<LineSegment> ConsolidateSegments(const std::vector<LineSegment>& raw,
                                             const BinaryImage& image,
                                             const ConsolidationOptions& options) {
  std::vector<size_t> order(raw.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t i, size_t j) { return raw[i].length() > raw[j].length(); });
  std::vector<Group> groups;
  for (size_t i : order) {
    auto it = std::find_if(groups.begin(), groups.end(),
                           [&](const Group& g) { return Joins(g, raw[i], options); });
    if (it == groups.end()) {
      groups.push_back({raw[i], 0.0, raw[i].length()});
    } else {
      Extend(*it, raw[i]);
    }
  }
  std::vector<LineSegment> result;
  for (const Group& g : groups) {
    const Eigen::Vector2d d = g.line.direction();
    LineSegment fitted = {g.line.a + g.t_min * d, g.line.a + g.t_max * d};
    // Repeated: the first band follows the Hough line, which may cross a thick edge slantwise
    // and so see more of it at one end; each refit centres the band better.
    Group current = g;
    for (int pass = 0; pass < 6; ++pass) {
      const auto pixels = BandPoints(current, image, options.fit_band_cells);
      if (int(pixels.size()) < options.min_fit_pixels) break;
      const LineSegment previous = fitted;
      fitted = Refit(current, pixels);
      current = {fitted, 0.0, fitted.length()};
      if (pass > 0 && (fitted.a - previous.a).norm() + (fitted.b - previous.b).norm() < 0.01) break;
    }
    if (fitted.length() >= options.min_length_cells) result.push_back(fitted);
  }
  std::stable_sort(result.begin(), result.end(), [](const LineSegment& x, const LineSegment& y) {
    return x.length() > y.length();
  });
  return WithoutDuplicates(result, options);
}

}  // namespace fleetmap::aggregator
