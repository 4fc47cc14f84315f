#include "vehicle_agent/candidate_watch.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "vehicle_agent/option_check.h"

namespace fleetmap::vehicle_agent {

core::Status CandidateWatchOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(
      CheckOption(pass_margin_m > 0, "CandidateWatchOptions.pass_margin_m", pass_margin_m, "> 0"));
  FLEETMAP_RETURN_IF_ERROR(
      CheckOption(hit_margin_m > 0, "CandidateWatchOptions.hit_margin_m", hit_margin_m, "> 0"));
  FLEETMAP_RETURN_IF_ERROR(CheckOption(min_free_scans >= 1, "CandidateWatchOptions.min_free_scans",
                                       min_free_scans, ">= 1"));
  FLEETMAP_RETURN_IF_ERROR(
      CheckOption(hold_gap_s > 0, "CandidateWatchOptions.hold_gap_s", hold_gap_s, "> 0"));
  FLEETMAP_RETURN_IF_ERROR(CheckOption(report_held_s >= 0, "CandidateWatchOptions.report_held_s",
                                       report_held_s, ">= 0"));
  return CheckOption(max_range_m > 0, "CandidateWatchOptions.max_range_m", max_range_m, "> 0");
}

CandidateWatch::CandidateWatch(const core::GridGeometry& geometry,
                               const CandidateWatchOptions& options)
    : geometry_(geometry), options_(options) {}

void CandidateWatch::SetCandidates(const std::vector<int64_t>& cells) {
  std::unordered_map<int64_t, Count> kept;
  kept.reserve(cells.size());
  for (int64_t c : cells) {
    if (c < 0 || c >= geometry_.num_cells()) continue;
    auto it = cells_.find(c);
    kept[c] = it == cells_.end() ? Count{} : it->second;
  }
  cells_.swap(kept);
  std::unordered_set<int64_t> still(cells.begin(), cells.end());
  auto gone = [&](int64_t c) { return !still.count(c); };
  seen_free_.erase(std::remove_if(seen_free_.begin(), seen_free_.end(), gone), seen_free_.end());
  held_.erase(std::remove_if(held_.begin(), held_.end(), gone), held_.end());
}

void CandidateWatch::RememberEnds(const core::LaserScan& scan, const core::Pose2& scanner_pose) {
  const double t = scan.stamp_s, gap = options_.hold_gap_s;
  for (size_t i = 0; i < scan.size(); ++i) {
    if (!scan.IsValidReturn(i) || scan.ranges_m[i] > options_.max_range_m) continue;
    const double a = scan.angle(i), r = scan.ranges_m[i];
    const core::CellIndex c =
        geometry_.WorldToCell(scanner_pose.Apply({r * std::cos(a), r * std::sin(a)}));
    if (!geometry_.Contains(c)) continue;
    const auto [it, first] = streaks_.try_emplace(geometry_.Index(c), Streak{t, t});
    if (!first && it->second.last_s < t - gap) it->second.since_s = t;  // after a pause
    it->second.last_s = t;
  }
  if (t - pruned_s_ < gap) return;  // forget what paused, once per hold_gap_s
  for (auto it = streaks_.begin(); it != streaks_.end();)
    it = it->second.last_s < t - gap ? streaks_.erase(it) : std::next(it);
  pruned_s_ = t;
}

double CandidateWatch::HeldSince(int64_t cell, double now_s) const {
  const int w = geometry_.width();
  const int x = static_cast<int>(cell % w), y = static_cast<int>(cell / w);
  double since = now_s;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const core::CellIndex n{x + dx, y + dy};
      if (!geometry_.Contains(n)) continue;
      const auto it = streaks_.find(geometry_.Index(n));
      if (it != streaks_.end() && it->second.last_s >= now_s - options_.hold_gap_s)
        since = std::min(since, it->second.since_s);
    }
  return since;
}

void CandidateWatch::Held(int64_t cell, Count& count, double now_s) {
  if (!count.holding || now_s - count.held_until_s > options_.hold_gap_s) {
    count.holding = true;
    count.held_reported = false;
    count.held_since_s = std::max(HeldSince(cell, now_s), count.passed_s);
  }
  count.held_until_s = now_s;
  if (options_.report_held_s > 0 && !count.held_reported &&
      count.held_until_s - count.held_since_s >= options_.report_held_s) {
    count.held_reported = true;
    held_.push_back(cell);
  }
}

// The beams whose bearing falls on the cell, and one more on each side: the cell is passed
// when every one of them went beyond it (a beam that grazes an object's edge has a neighbour
// that ends on the object), ended at when one of them ended there, and otherwise nothing is
// said (something in front, no usable return, out of the field of view).
CandidateWatch::Beam CandidateWatch::Judge(const core::LaserScan& scan,
                                           const core::Pose2& map_to_scanner, int64_t cell) const {
  const core::CellIndex c{static_cast<int>(cell % geometry_.width()),
                          static_cast<int>(cell / geometry_.width())};
  const Eigen::Vector2d local = map_to_scanner.Apply(geometry_.CellCenter(c));
  const double range = local.norm();
  if (range > options_.max_range_m || range < scan.range_min_m) return Beam::kNone;
  const double half_width_rad = std::atan2(0.5 * geometry_.resolution_m(), range);
  const double centre =
      (std::atan2(local.y(), local.x()) - scan.angle_min_rad) / scan.angle_increment_rad;
  const double spread = std::abs(half_width_rad / scan.angle_increment_rad);
  const double first = std::floor(centre - spread) - 1.0, last = std::ceil(centre + spread) + 1.0;
  if (!(first >= 0 && last < static_cast<double>(scan.size()))) return Beam::kNone;
  bool all_passed = true;
  for (size_t i = static_cast<size_t>(first); i <= static_cast<size_t>(last); ++i) {
    const float r = scan.ranges_m[i];
    // No return within the scanner's range: the beam went through everything up to it.
    const bool through = std::isfinite(r) ? r >= scan.range_max_m : r > 0;
    if (through || (scan.IsValidReturn(i) && r >= range + options_.pass_margin_m)) continue;
    if (scan.IsValidReturn(i) && std::abs(r - range) <= options_.hit_margin_m) return Beam::kEnded;
    all_passed = false;
  }
  return all_passed ? Beam::kPassed : Beam::kNone;
}

void CandidateWatch::Observe(const core::LaserScan& scan, const core::Pose2& scanner_pose) {
  if (scan.size() == 0 || scan.angle_increment_rad == 0.0 || !scanner_pose.IsFinite()) return;
  if (options_.report_held_s > 0) RememberEnds(scan, scanner_pose);
  const core::Pose2 map_to_scanner = scanner_pose.Inverse();  // once per scan, not per cell
  for (auto& [cell, count] : cells_) {
    switch (Judge(scan, map_to_scanner, cell)) {
      case Beam::kNone:
        break;
      case Beam::kEnded:  // something is there now: start counting again
        count.free_scans = 0;
        count.reported = false;
        Held(cell, count, scan.stamp_s);
        break;
      case Beam::kPassed:
        count.holding = false;
        count.passed_s = scan.stamp_s;
        if (count.free_scans == 0) count.first_pass_s = scan.stamp_s;
        count.last_pass_s = scan.stamp_s;
        if (++count.free_scans == options_.min_free_scans && !count.reported) {
          count.reported = true;
          seen_free_.push_back(cell);
        }
        break;
    }
  }
}

CandidatesSeenFree CandidateWatch::TakeSeenFree() {
  CandidatesSeenFree out;
  std::sort(seen_free_.begin(), seen_free_.end());
  for (int64_t cell : seen_free_) {
    const Count& count = cells_.at(cell);
    if (out.cells.empty()) out.first_pass_s = count.first_pass_s;
    out.first_pass_s = std::min(out.first_pass_s, count.first_pass_s);
    out.last_pass_s = std::max(out.last_pass_s, count.last_pass_s);
    out.cells.push_back(cell);
  }
  seen_free_.clear();
  return out;
}

CandidatesHeld CandidateWatch::TakeHeld() {
  CandidatesHeld out;
  std::sort(held_.begin(), held_.end());
  for (int64_t cell : held_) {
    const Count& count = cells_.at(cell);
    out.cells.push_back(cell);
    out.since_s.push_back(count.held_since_s);
    out.until_s.push_back(count.held_until_s);
  }
  held_.clear();
  return out;
}

}  // namespace fleetmap::vehicle_agent
