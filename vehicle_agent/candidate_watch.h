// The fleet map's candidates that this vehicle's beams pass through while it drives. A
// candidate is a place the aggregator saw occupied once and waits to see again before it adds
// it: a pallet put down, or a person who turned there. A person comes back to a turning point,
// and a forklift to the place it stops, every few tens of seconds, and a temporary map that
// sees them there again would confirm them; but the vehicles build temporary maps only where
// their map does not explain their scans, so nobody looks at the place while it is empty.
// The vehicle does look: each scan's beams pass through the places it sees. A candidate that
// beams of several scans passed through, and none ended at, is reported as seen free, and the
// aggregator drops it (docs/aggregator.md, "People and forklifts").
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "core/map/grid_geometry.h"
#include "core/map/seen_free_cells.h"
#include "core/pose2.h"
#include "core/result.h"
#include "core/scan.h"

namespace fleetmap::vehicle_agent {

struct CandidateWatchOptions {
  // A beam passes through a cell when its return lies at least this far beyond the cell's
  // centre, metres: half a cell's diagonal at 0.10 m (0.07) plus three standard deviations of
  // a safety scanner's range noise (3 x 0.03 m).
  double pass_margin_m = 0.16;
  // ... and ends at it when its return lies within this of the centre, metres: the same half
  // diagonal plus noise. A beam that ends short of the cell (something in front) says nothing.
  double hit_margin_m = 0.16;
  // Seen free: passed by beams of at least this many scans, with no beam ending at it since
  // the last time one did (at 25 scans/s, a fifth of a second of looking).
  int min_free_scans = 5;
  // Cells farther than this from the scanner are not judged, metres: far beams are wide and
  // a small angular error of the pose moves them by more than a cell.
  double max_range_m = 15.0;
  // A cell that this vehicle's beams keep ending at, never longer apart than hold_gap_s
  // (seconds > 0), is held; a pass through it or a longer pause ends the hold. A candidate
  // held report_held_s (seconds; 0: never reported) is reported held: something that stayed
  // longer than a person waits or a forklift stops (the aggregator adds it when the hold
  // lasted its confirm_min_gap_s). The hold of a new candidate starts where the beams began
  // to end at it (or at a neighbour), before the aggregator made it a candidate: one pass past
  // a pallet can be enough. Off by default: at 10 s the generator's forklifts, which stop and
  // turn in place for up to 11 s, are held; at 13 s candidates drawn in front of a wall by a
  // map placed off are held by the beams that end on the wall
  // (docs/experiments/2026-12-05-wall-offset-and-holds.md).
  double hold_gap_s = 1.0;
  double report_held_s = 0.0;
  core::Status Validate() const;
};

using CandidatesHeld = core::HeldCells;

// The batch a vehicle reports: the aggregator drops a candidate only when the batch's first
// pass came after the last temporary map that saw it occupied.
using CandidatesSeenFree = core::SeenFreeCells;

class CandidateWatch {
 public:
  // `geometry`: the fleet map's grid, whose cell indices the candidates are.
  CandidateWatch(const core::GridGeometry& geometry, const CandidateWatchOptions& options);

  // The aggregator's current candidates (replacing the last set); what was counted for a cell
  // that stays a candidate is kept, a cell already reported is not reported again.
  void SetCandidates(const std::vector<int64_t>& cells);

  // One scan taken at `scanner_pose` (the scanner in the map frame), from a vehicle that is
  // localized: a lost vehicle's beams would pass through the wrong cells.
  void Observe(const core::LaserScan& scan, const core::Pose2& scanner_pose);

  // The candidates seen free since the last call (empty cells: none).
  CandidatesSeenFree TakeSeenFree();
  // The candidates held report_held_s since the last call (each once per hold).
  CandidatesHeld TakeHeld();

  size_t num_candidates() const { return cells_.size(); }
  const core::GridGeometry& geometry() const { return geometry_; }

 private:
  struct Count {
    int free_scans = 0;
    double first_pass_s = 0.0, last_pass_s = 0.0;
    bool reported = false;
    bool holding = false, held_reported = false;
    double held_since_s = 0.0, held_until_s = 0.0;
    double passed_s = -1e300;  // the last scan whose beams passed through it
  };
  // Where beam ends fell, with no pause longer than hold_gap_s: since when, and the last time.
  struct Streak {
    double since_s = 0.0, last_s = 0.0;
  };
  void RememberEnds(const core::LaserScan& scan, const core::Pose2& scanner_pose);
  // When beams began to end at the cell or a neighbour of it without a pause; `now_s` if not.
  double HeldSince(int64_t cell, double now_s) const;
  void Held(int64_t cell, Count& count, double now_s);
  enum class Beam { kNone, kPassed, kEnded };
  // `map_to_scanner`: the inverse of the scanner's pose in the map.
  Beam Judge(const core::LaserScan& scan, const core::Pose2& map_to_scanner, int64_t cell) const;

  core::GridGeometry geometry_;
  CandidateWatchOptions options_;
  std::unordered_map<int64_t, Count> cells_;
  std::vector<int64_t> seen_free_;
  std::vector<int64_t> held_;
  std::unordered_map<int64_t, Streak> streaks_;  // cells beams ended at within hold_gap_s
  double pruned_s_ = -1e300;
};

}  // namespace fleetmap::vehicle_agent
