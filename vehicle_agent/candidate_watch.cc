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
  seen_free_.erase(std::remove_if(seen_free_.begin(), seen_free_.end(),
                                  [&](int64_t c) { return !still.count(c); }),
                   seen_free_.end());
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
  const core::Pose2 map_to_scanner = scanner_pose.Inverse();  // once per scan, not per cell
  for (auto& [cell, count] : cells_) {
    switch (Judge(scan, map_to_scanner, cell)) {
      case Beam::kNone:
        break;
      case Beam::kEnded:  // something is there now: start counting again
        count.free_scans = 0;
        count.reported = false;
        break;
      case Beam::kPassed:
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

}  // namespace fleetmap::vehicle_agent
