#include "aggregator/alignment/line_matcher.h"

#include <algorithm>
#include <cmath>

namespace fleetmap::aggregator {
namespace {

double DirectionAngle(const LineSegment& s) { return LineDirectionAngle(s.direction()); }

LineMatch Measure(const std::vector<LineSegment>& temp, const std::vector<LineSegment>& stat, int t,
                  int s) {
  LineMatch m;
  m.temp_index = t;
  m.static_index = s;
  m.angle_diff_rad = LineAngleDiff(DirectionAngle(temp[t]), DirectionAngle(stat[s]));
  m.normal = stat[s].normal();
  m.offset_m = -stat[s].SignedDistance(temp[t].midpoint());
  m.weight_m = temp[t].length();
  return m;
}

// Static segments the normal from t's mid point meets within the windows, nearest first.
// `static_angles` are the static segments' direction angles (computed once per call).
std::vector<LineMatch> Candidates(const std::vector<LineSegment>& temp,
                                  const std::vector<LineSegment>& stat,
                                  const std::vector<double>& static_angles, int t,
                                  const LineMatchOptions& o) {
  std::vector<LineMatch> found;
  const Eigen::Vector2d mid = temp[t].midpoint();
  const double temp_angle = DirectionAngle(temp[t]);
  for (int s = 0; s < static_cast<int>(stat.size()); ++s) {
    if (std::abs(LineAngleDiff(temp_angle, static_angles[s])) > o.max_angle_diff_rad ||
        temp[t].FacesAwayFrom(stat[s])) {
      continue;
    }
    const double along = stat[s].Along(mid);
    if (along < -o.extent_margin_m || along > stat[s].length() + o.extent_margin_m) continue;
    const LineMatch m = Measure(temp, stat, t, s);
    if (std::abs(m.offset_m) <= o.max_normal_offset_m) found.push_back(m);
  }
  std::stable_sort(found.begin(), found.end(), [](const LineMatch& a, const LineMatch& b) {
    return std::abs(a.offset_m) < std::abs(b.offset_m);
  });
  return found;
}

// Offsets of two matches compared along the same normal (normals of parallel lines can
// point opposite ways where theta wraps from pi to 0).
bool OffsetsAgree(const LineMatch& a, const LineMatch& b, double tolerance) {
  const double sign = a.normal.dot(b.normal) >= 0 ? 1.0 : -1.0;
  return std::abs(a.offset_m - sign * b.offset_m) <= tolerance;
}

// For candidate `c` of one temporary segment: the length of the other parallel temporary
// segments with a candidate that keeps the pair's separation.
double PairSupport(const LineMatch& c, const std::vector<std::vector<LineMatch>>& all,
                   const std::vector<LineSegment>& temp, const LineMatchOptions& o) {
  double support = 0.0;
  for (const auto& other : all) {
    if (other.empty() || other.front().temp_index == c.temp_index) continue;
    const int k = other.front().temp_index;
    if (std::abs(LineAngleDiff(DirectionAngle(temp[c.temp_index]), DirectionAngle(temp[k]))) >
        o.parallel_tolerance_rad) {
      continue;
    }
    for (const LineMatch& d : other) {
      if (d.static_index == c.static_index || !OffsetsAgree(c, d, o.pair_tolerance_m)) continue;
      support += temp[k].length();
      break;
    }
  }
  return support;
}

}  // namespace

core::Status LineMatchOptions::Validate() const {
  if (!(max_angle_diff_rad > 0 && max_angle_diff_rad < M_PI / 4))
    return core::InvalidArgument("matching.max_angle_diff_rad must be in (0, pi/4)");
  if (!(max_normal_offset_m > 0))
    return core::InvalidArgument("matching.max_normal_offset_m must be > 0");
  if (!(extent_margin_m >= 0))
    return core::InvalidArgument("matching.extent_margin_m must be >= 0");
  if (!(min_temp_length_m >= 0))
    return core::InvalidArgument("matching.min_temp_length_m must be >= 0");
  if (!(parallel_tolerance_rad > 0))
    return core::InvalidArgument("matching.parallel_tolerance_rad must be > 0");
  if (!(pair_tolerance_m > 0))
    return core::InvalidArgument("matching.pair_tolerance_m must be > 0");
  return core::OkStatus();
}

std::vector<LineMatch> MatchLines(const std::vector<LineSegment>& temp_in_map,
                                  const std::vector<LineSegment>& static_lines,
                                  const LineMatchOptions& options) {
  std::vector<double> static_angles;
  for (const LineSegment& s : static_lines) static_angles.push_back(DirectionAngle(s));
  std::vector<std::vector<LineMatch>> candidates;
  for (int t = 0; t < static_cast<int>(temp_in_map.size()); ++t) {
    if (temp_in_map[t].length() < options.min_temp_length_m) continue;
    auto c = Candidates(temp_in_map, static_lines, static_angles, t, options);
    if (!c.empty()) candidates.push_back(std::move(c));
  }
  std::vector<LineMatch> matches;
  for (auto& list : candidates) {
    if (options.use_pairs) {
      for (LineMatch& c : list) c.support_m = PairSupport(c, candidates, temp_in_map, options);
    }
    // Most support wins; among equals the nearest (the list is sorted by distance).
    const auto best = std::max_element(list.begin(), list.end(), [](const auto& a, const auto& b) {
      return a.support_m < b.support_m;
    });
    matches.push_back(*best);
  }
  return matches;
}

void UpdateMatches(const std::vector<LineSegment>& temp_in_map,
                   const std::vector<LineSegment>& static_lines, std::vector<LineMatch>& matches) {
  for (LineMatch& m : matches) {
    const double support = m.support_m;
    m = Measure(temp_in_map, static_lines, m.temp_index, m.static_index);
    m.support_m = support;
  }
}

}  // namespace fleetmap::aggregator
