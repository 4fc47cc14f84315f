#include "aggregator/alignment/alignment.h"

#include <cmath>

#include "aggregator/alignment/alignment_steps.h"

namespace fleetmap::aggregator {
namespace {

Eigen::Vector2d Perpendicular(const Eigen::Vector2d& d) { return {-d.y(), d.x()}; }

// The matching of every round after the first, once a correction is applied.
LineMatchOptions RefinedMatching(const AlignmentOptions& o) {
  LineMatchOptions refined = o.matching;
  refined.max_normal_offset_m = o.refined_max_normal_offset_m;
  return refined;
}

// Fills the report fields from the final correction.
void Finish(const AlignmentInput& in, const StaticMapFeatures& f, const LineMatchOptions& matching,
            AlignmentResult& r) {
  const core::Pose2 placed = r.correction * in.anchor;
  r.temp_lines_in_map = PlaceSegments(in.temp_lines, placed);
  r.matches = MatchLines(r.temp_lines_in_map, f.lines(), matching);
  const Eigen::Vector2d moved =
      r.correction.Apply(in.anchor.translation()) - in.anchor.translation();
  r.dtheta_rad = r.correction.theta_rad;
  r.dx_m = moved.dot(r.axis_x);
  r.dy_m = moved.dot(r.axis_y);
}

// ---- The paper's mode ----

AlignmentResult AlignPaper(const AlignmentInput& in, const StaticMapFeatures& f,
                           const AlignmentOptions& o) {
  AlignmentResult r;
  r.rounds = 1;
  const double yaw = f.geometry().origin().theta_rad;  // the picture's axes in the static frame
  r.axis_x = {std::cos(yaw), std::sin(yaw)};
  r.axis_y = Perpendicular(r.axis_x);
  auto placed = PlaceSegments(in.temp_lines, in.anchor);
  std::vector<LineMatch> matches = MatchLines(placed, f.lines(), o.matching);
  std::vector<Weighted> angles, dys;
  for (const LineMatch& m : matches) angles.push_back({m.angle_diff_rad, m.weight_m});
  // dtheta about the temporary map's origin (where the vehicle started it).
  const core::Pose2 turn = RotationAbout(in.anchor.translation(), WeightedMean(angles));
  UpdateMatches(PlaceSegments(in.temp_lines, turn * in.anchor), f.lines(), matches);
  for (const LineMatch& m : matches) {
    const double across = m.normal.dot(r.axis_y);
    if (std::abs(across) >= std::sqrt(0.5)) dys.push_back({m.offset_m / across, m.weight_m});
  }
  const Eigen::Vector2d dy = WeightedMean(dys) * r.axis_y;
  const auto points = PlacePoints(Subsample(in.temp_points, o.max_search_points),
                                  Translation(dy) * turn * in.anchor);
  r.overlap = SearchShift(f, points, r.axis_x, o.paper_overlap);
  r.shift_by_overlap = true;
  r.correction = Translation(dy + r.overlap.shift_m * r.axis_x) * turn;
  Finish(in, f, o.matching, r);
  return r;
}

// ---- Ours: dominant directions, robust, iterated ----

struct Family {
  Eigen::Vector2d along, across;  // the direction, and its normal
};

// Matches whose temporary line runs along `family`, with offsets measured along its normal.
std::vector<Weighted> FamilyOffsets(const std::vector<LineMatch>& matches, const Family& family,
                                    double tolerance) {
  std::vector<Weighted> offsets;
  for (const LineMatch& m : matches) {
    const double across = m.normal.dot(family.across);
    if (std::abs(across) < std::cos(tolerance)) continue;
    offsets.push_back({m.offset_m / across, m.weight_m});
  }
  return offsets;
}

double TotalWeight(const std::vector<Weighted>& samples) {
  double total = 0.0;
  for (const Weighted& s : samples) total += s.weight;
  return total;
}

// Solves n1 . t = a1 and n2 . t = a2 for t.
Eigen::Vector2d SolveAcross(const Family& f1, double a1, const Family& f2, double a2) {
  Eigen::Matrix2d n;
  n.row(0) = f1.across.transpose();
  n.row(1) = f2.across.transpose();
  return n.inverse() * Eigen::Vector2d(a1, a2);
}

// The translation of one round: across each family by its lines; along a family whose
// crossing direction has too little line length, by the overlap search.
Eigen::Vector2d RoundTranslation(const AlignmentInput& in, const StaticMapFeatures& f,
                                 const AlignmentOptions& o, const std::vector<LineMatch>& matches,
                                 const core::Pose2& correction, int round, AlignmentResult& r) {
  const DominantDirections& d = f.directions();
  const Family f1{d.primary(), Perpendicular(d.primary())};
  const Family f2{d.secondary(), Perpendicular(d.secondary())};
  const auto o1 = FamilyOffsets(matches, f1, o.family_tolerance_rad);
  const auto o2 = FamilyOffsets(matches, f2, o.family_tolerance_rad);
  const bool fixed1 = TotalWeight(o1) >= o.min_family_length_m;
  const bool fixed2 = TotalWeight(o2) >= o.min_family_length_m;
  const double a1 = RobustWeightedMean(o1, o.offset_inlier_m);
  const double a2 = RobustWeightedMean(o2, o.offset_inlier_m);
  if (fixed1 && fixed2) return SolveAcross(f1, a1, f2, a2);
  if (!fixed1 && !fixed2) return Eigen::Vector2d::Zero();
  const Family& known = fixed1 ? f1 : f2;
  const Eigen::Vector2d across = (fixed1 ? a1 : a2) * known.across;
  OverlapSearchOptions search = o.overlap;
  if (round > 0) search.range_m = o.refined_search_range_m;
  const auto points = PlacePoints(Subsample(in.temp_points, o.max_search_points),
                                  Translation(across) * correction * in.anchor);
  const OverlapPeak peak = SearchShift(f, points, known.along, search);
  if (!r.shift_by_overlap) r.overlap = peak;  // the first search spans the whole range
  r.shift_by_overlap = true;
  return across + peak.shift_m * known.along;
}

// Matches of lines along either dominant direction.
std::vector<LineMatch> InFamilies(const std::vector<LineMatch>& matches, const StaticMapFeatures& f,
                                  double tolerance) {
  std::vector<LineMatch> kept;
  for (const LineMatch& m : matches) {
    const Eigen::Vector2d along = Perpendicular(m.normal);
    if (std::abs(along.dot(f.directions().primary())) >= std::cos(tolerance) ||
        std::abs(along.dot(f.directions().secondary())) >= std::cos(tolerance)) {
      kept.push_back(m);
    }
  }
  return kept;
}

AlignmentResult AlignOurs(const AlignmentInput& in, const StaticMapFeatures& f,
                          const AlignmentOptions& o) {
  AlignmentResult r;
  r.axis_x = f.directions().primary();
  r.axis_y = Perpendicular(r.axis_x);
  const LineMatchOptions refined = RefinedMatching(o);
  for (int round = 0; round < o.iterations; ++round) {
    const LineMatchOptions& window = round == 0 ? o.matching : refined;
    auto placed = PlaceSegments(in.temp_lines, r.correction * in.anchor);
    auto matches = InFamilies(MatchLines(placed, f.lines(), window), f, o.family_tolerance_rad);
    if (matches.empty()) break;
    std::vector<Weighted> angles;
    // The angle of a line fitted to n points along length L varies as 1 / (n L^2) ~ 1 / L^3.
    for (const LineMatch& m : matches)
      angles.push_back({m.angle_diff_rad, m.weight_m * m.weight_m * m.weight_m});
    const double dtheta = RobustWeightedMean(angles, o.rotation_inlier_rad);
    // About the anchor as placed so far: what is left is its translation error, no lever.
    const Eigen::Vector2d pivot = (r.correction * in.anchor).translation();
    r.correction = RotationAbout(pivot, dtheta) * r.correction;
    placed = PlaceSegments(in.temp_lines, r.correction * in.anchor);
    matches = InFamilies(MatchLines(placed, f.lines(), window), f, o.family_tolerance_rad);
    const Eigen::Vector2d t = RoundTranslation(in, f, o, matches, r.correction, round, r);
    r.correction = Translation(t) * r.correction;
    r.rounds = round + 1;
    if (std::abs(dtheta) < 1e-5 && t.norm() < 0.1 * f.geometry().resolution_m()) break;
  }
  Finish(in, f, refined, r);
  return r;
}

}  // namespace

const char* AlignmentModeName(AlignmentMode mode) {
  return mode == AlignmentMode::kPaper ? "paper" : "ours";
}

core::Result<AlignmentMode> ParseAlignmentMode(const std::string& name) {
  if (name == "paper") return AlignmentMode::kPaper;
  if (name == "ours") return AlignmentMode::kDominantDirections;
  return core::InvalidArgument("unknown alignment mode '" + name + "' (known: ours, paper)");
}

core::Status AlignmentOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(matching.Validate());
  FLEETMAP_RETURN_IF_ERROR(overlap.Validate());
  FLEETMAP_RETURN_IF_ERROR(paper_overlap.Validate());
  if (!(refined_max_normal_offset_m > 0))
    return core::InvalidArgument("alignment.refined_max_normal_offset_m must be > 0");
  if (iterations < 1) return core::InvalidArgument("alignment.iterations must be >= 1");
  if (!(family_tolerance_rad > 0 && family_tolerance_rad < M_PI / 4))
    return core::InvalidArgument("alignment.family_tolerance_rad must be in (0, pi/4)");
  if (!(rotation_inlier_rad > 0))
    return core::InvalidArgument("alignment.rotation_inlier_rad must be > 0");
  if (!(offset_inlier_m > 0)) return core::InvalidArgument("alignment.offset_inlier_m must be > 0");
  if (!(min_family_length_m >= 0))
    return core::InvalidArgument("alignment.min_family_length_m must be >= 0");
  if (!(refined_search_range_m > 0))
    return core::InvalidArgument("alignment.refined_search_range_m must be > 0");
  if (max_search_points < 10)
    return core::InvalidArgument("alignment.max_search_points must be >= 10");
  return core::OkStatus();
}

std::vector<Eigen::Vector2d> Subsample(const std::vector<Eigen::Vector2d>& points, int max_points) {
  if (static_cast<int>(points.size()) <= max_points) return points;
  const size_t stride = (points.size() + max_points - 1) / static_cast<size_t>(max_points);
  std::vector<Eigen::Vector2d> kept;
  for (size_t i = 0; i < points.size(); i += stride) kept.push_back(points[i]);
  return kept;
}

AlignmentResult Align(const AlignmentInput& input, const StaticMapFeatures& features,
                      const AlignmentOptions& options) {
  return options.mode == AlignmentMode::kPaper ? AlignPaper(input, features, options)
                                               : AlignOurs(input, features, options);
}

AlignmentResult WithCorrection(const AlignmentInput& input, const StaticMapFeatures& features,
                               const AlignmentOptions& options, const core::Pose2& correction) {
  AlignmentResult r;
  r.axis_x = features.directions().primary();
  r.axis_y = Perpendicular(r.axis_x);
  r.correction = correction;
  Finish(input, features, RefinedMatching(options), r);
  return r;
}

}  // namespace fleetmap::aggregator
