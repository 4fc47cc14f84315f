#include "aggregator/alignment/overlap_search.h"

#include <algorithm>
#include <cmath>

namespace fleetmap::aggregator {
namespace {

struct Sample {
  double shift = 0.0;
  double score = 0.0;
};

std::vector<Sample> Scan(const StaticMapFeatures& f, const std::vector<Eigen::Vector2d>& points,
                         const Eigen::Vector2d& direction, double from, double to, double step,
                         OverlapScore score) {
  std::vector<Sample> samples;
  const int n = static_cast<int>(std::floor((to - from) / step + 1e-9));
  for (int i = 0; i <= n; ++i) {
    const double s = from + i * step;
    samples.push_back({s, OverlapScoreAt(f, points, s * direction, score)});
  }
  return samples;
}

// The best sample; among equal scores the one nearest to zero shift.
Sample Best(const std::vector<Sample>& samples) {
  Sample best{0.0, -1.0};
  for (const Sample& s : samples) {
    if (s.score > best.score || (s.score == best.score && std::abs(s.shift) < std::abs(best.shift)))
      best = s;
  }
  return best;
}

// The best local peak of the whole steps at least `separation` from `best`: a step no lower
// than its neighbours (an end of the range counts, with its one neighbour). The lowest score
// when there is none.
double Rival(const std::vector<Sample>& samples, const Sample& best, double separation,
             double lowest) {
  double rival = lowest;
  for (size_t i = 0; i < samples.size(); ++i) {
    if (std::abs(samples[i].shift - best.shift) < separation - 1e-9) continue;
    const bool left = i == 0 || samples[i].score >= samples[i - 1].score;
    const bool right = i + 1 == samples.size() || samples[i].score >= samples[i + 1].score;
    if (left && right) rival = std::max(rival, samples[i].score);
  }
  return rival;
}

// Vertex of the parabola through three equally spaced samples around the best one.
double ParabolaVertex(const std::vector<Sample>& fine, const Sample& best, double step) {
  for (size_t i = 1; i + 1 < fine.size(); ++i) {
    if (fine[i].shift != best.shift) continue;
    const double a = fine[i - 1].score, b = fine[i].score, c = fine[i + 1].score;
    const double denominator = a - 2 * b + c;
    if (denominator >= 0) return best.shift;
    return best.shift + 0.5 * step * (a - c) / denominator;
  }
  return best.shift;
}

}  // namespace

core::Status OverlapSearchOptions::Validate() const {
  if (!(range_m > 0)) return core::InvalidArgument("overlap.range_m must be > 0");
  if (!(step_m > 0)) return core::InvalidArgument("overlap.step_m must be > 0");
  if (!(refine_step_m >= 0 && refine_step_m < step_m))
    return core::InvalidArgument("overlap.refine_step_m must be in [0, step_m)");
  if (!(rival_separation_m >= step_m))
    return core::InvalidArgument("overlap.rival_separation_m must be >= step_m");
  return core::OkStatus();
}

double OverlapScoreAt(const StaticMapFeatures& f, const std::vector<Eigen::Vector2d>& points,
                      const Eigen::Vector2d& shift, OverlapScore score) {
  if (points.empty()) return 0.0;
  double sum = 0.0;
  for (const Eigen::Vector2d& p : points) {
    sum += score == OverlapScore::kOccupiedCells ? double(f.OnOccupied(p + shift))
                                                 : f.SurfaceField(p + shift);
  }
  return sum / double(points.size());
}

OverlapPeak SearchShift(const StaticMapFeatures& f, const std::vector<Eigen::Vector2d>& points,
                        const Eigen::Vector2d& direction, const OverlapSearchOptions& o) {
  const auto coarse = Scan(f, points, direction, -o.range_m, o.range_m, o.step_m, o.score);
  Sample best = Best(coarse);
  OverlapPeak peak;
  peak.lowest = best.score;
  for (const Sample& c : coarse) peak.lowest = std::min(peak.lowest, c.score);
  peak.at_edge = best.shift == coarse.front().shift || best.shift == coarse.back().shift;
  peak.step_best = best.score;
  peak.rival = Rival(coarse, best, o.rival_separation_m, peak.lowest);
  peak.at_zero = OverlapScoreAt(f, points, Eigen::Vector2d::Zero(), o.score);
  if (o.refine_step_m > 0) {
    const auto fine = Scan(f, points, direction, best.shift - o.step_m, best.shift + o.step_m,
                           o.refine_step_m, o.score);
    best = Best(fine);
    best.shift = ParabolaVertex(fine, best, o.refine_step_m);
  }
  peak.shift_m = best.shift;
  peak.score = best.score;
  return peak;
}

double ExplainedFraction(const StaticMapFeatures& f, const std::vector<Eigen::Vector2d>& points) {
  if (points.empty()) return 0.0;
  int explained = 0;
  for (const Eigen::Vector2d& p : points) explained += f.SurfaceField(p) >= 0.5;
  return double(explained) / double(points.size());
}

}  // namespace fleetmap::aggregator
