// The merge rules (the paper, Sec. 3.4; docs/aggregator.md): a cell the temporary map observed
// occupied where the static map is free becomes a semi-static obstacle; a semi-static cell
// it observed free with enough evidence is removed; static cells never change. Planned in
// two phases like nav2's layered costmap: the placed map's window bounds the work, then only
// cells inside it are decided, so the delta covers only the tiles that really changed.
//
// Semi-static means still there later. With confirmations = 2 (the default) a cell first
// seen occupied becomes a candidate, and only a temporary map of another time (their time
// spans lie confirm_min_gap_s apart, and at most confirm_max_gap_s) that sees it, or a cell
// next to it, occupied again adds it; so does a confirmed obstacle next to it (another face of
// the same pallet). A candidate seen free is dropped; one too old to confirm that is seen
// again starts afresh. A person or a forklift is not at the same place in two such maps, a
// pallet is. Nor is one seen occupied by every map of a watch that lasts confirm_min_gap_s
// (maps each starting when the last one that saw the cell ended, as a vehicle's temporary
// maps follow each other while it passes), which also adds it with confirm_by_watch: one pass
// of one vehicle past a new pallet is enough, a person standing for a few seconds is not.
// confirmations = 1 adds at first sight, as the paper does.
#pragma once

#include <map>
#include <vector>

#include "aggregator/alignment/placement.h"
#include "aggregator/merge_commit.h"
#include "core/map/occupancy_grid.h"

namespace fleetmap::aggregator {

struct MergeOptions {
  // Temporary log-odds at or above this add an obstacle (> 0). 3.0 needs two clean hits
  // (2.2 each) more than misses: a stray return one cell deep inside a pallet stays out,
  // which one hit (1.5) would add (docs/experiments/2026-12-01-merge-options.md).
  float add_min_log_odds = 3.0f;
  // At or below this a semi-static obstacle is removed (< 0): about five free observations
  // (0.4 each) more than hits.
  float remove_max_log_odds = -2.0f;
  // Distances below are in metres, used on the map's grid as the nearest whole number of
  // cells (at least one where the distance is > 0; MergeCells): the same building at 3 or
  // 10 cm keeps the same clearances.
  // Cells this close (Chebyshev, metres) to an occupied static cell are never added: range
  // noise and a fraction of a cell of alignment error put a wall's hits onto the free cells
  // in front of it, which are no obstacle. 0..0.5 m; 0.10 m is 2 cells at 5 cm.
  double static_clearance_m = 0.10;
  // A temporary map placed a little off draws the walls it saw beside the static ones, as a
  // second wall in front of them. Its hits within this distance (metres) of a static wall
  // measure how far off: where nine in ten of them lie within d of the wall, that map adds
  // nothing within d of a static wall either (never less than static_clearance_m). 0 switches
  // this off; at most 0.5 m.
  double wall_offset_window_m = 0.3;
  // A candidate a vehicle reports held (its beams kept ending there, CANDIDATES_HELD_<id>)
  // is not added when it lies this close (Chebyshev, metres) to a static wall: beams that end
  // on the wall end within the vehicle's hit margin (0.16 m) of the cells in front of it, so a
  // candidate drawn there by a temporary map placed a little off is held by the wall itself.
  // 0..0.5 m; such a candidate can still be confirmed by a second temporary map.
  double held_wall_clearance_m = 0.2;
  // An added cell needs this many of its 8 neighbours at add_min_log_odds too, so an
  // isolated hit (a mixed pixel at a depth edge) is no obstacle. 0..8.
  int min_occupied_neighbours = 1;
  // A semi-static cell is removed only when no cell this close (Chebyshev, metres) holds
  // evidence at add_min_log_odds and every semi-static cell this close is seen free (< 0)
  // too: the edge of an obstacle that is still there flickers between hit and passed, and a
  // map a little off may see a strip of it free; an obstacle taken away leaves its whole
  // neighbourhood free. 0..0.5 m. 0.10 m (2 cells at 5 cm) rather than 0.05: with one cell
  // the edges of pallets that stay (second rows of cells, added from a neighbour's sighting)
  // are removed and added again, and two lose no true removal (docs/aggregator.md, "Change
  // detection of the real system").
  double removal_clearance_m = 0.10;
  // Temporary maps of different times that must see a cell occupied before it is added:
  // 1 (the paper: at first sight) or 2 (a candidate first, see above).
  int confirmations = 2;
  // A confirmation may come from evidence this close (Chebyshev, metres): the edge of a
  // pallet seen from another side or another grid phase falls into the next cell. 0..0.3 m.
  double confirm_radius_m = 0.05;
  // The two maps must lie at least this far apart in time, seconds >= 0: longer than a
  // person or a forklift stands still (a person waits a few seconds at a door or a turn, a
  // forklift stops for a pick), which maps 2 s apart both saw standing; a pallet is still
  // there on the vehicle's next pass or for the next vehicle. 10 s across the world suite
  // (docs/aggregator.md, "People and forklifts").
  double confirm_min_gap_s = 10.0;
  // ... and at most this far apart, seconds > confirm_min_gap_s: a candidate older than
  // this is renewed by a new sighting, not confirmed. Long enough for the next pass of a
  // vehicle whose first pass saw the pallet for less than confirm_min_gap_s (an office
  // corridor); a person who comes back to the same place is no candidate any more once a
  // map in between saw the place free, or saw the person leave it (core/map/moving_cells.h).
  double confirm_max_gap_s = 120.0;
  // Whether a watch of confirm_min_gap_s confirms (see above). Off by default: on the world
  // suite it is about even, it serves the single-vehicle scenarios, and in a small room it
  // adds more faces of a box than a later pass sees free, so that half of the box stays
  // after it is taken away (docs/aggregator.md, "People and forklifts").
  bool confirm_by_watch = false;
  // A map that starts at most this long after the end of the last map that saw a candidate
  // continues its watch, seconds >= 0 (a vehicle's next temporary map starts within a scan
  // period of the last one's end; a pause longer than this breaks the watch).
  double watch_join_s = 1.0;
  core::OccupancyThresholds thresholds;  // classify the static map's cells
  core::Status Validate() const;
};

// The distances of MergeOptions in cells of a grid.
struct MergeCells {
  int static_clearance = 0;
  int removal_clearance = 0;
  int confirm_radius = 0;
};
MergeCells MergeCellsFor(const MergeOptions& options, double resolution_m);
// The nearest whole number of cells to `distance_m`, at least 1 where it is > 0.
int CellsFor(double distance_m, double resolution_m);

// Per static cell: 1 where an obstacle may be added (free, and clear of static cells by
// static_clearance_m).
std::vector<uint8_t> AddableCells(const core::OccupancyGrid& static_map,
                                  const MergeOptions& options);
// ... from the map's WallDistances, when they are at hand.
std::vector<uint8_t> AddableCells(const core::OccupancyGrid& static_map,
                                  const MergeOptions& options,
                                  const std::vector<uint8_t>& wall_distance);

// Per static cell: its Chebyshev distance in cells to the nearest occupied static cell, at
// most 255 (also where there is none).
std::vector<uint8_t> WallDistances(const core::OccupancyGrid& static_map,
                                   const core::OccupancyThresholds& thresholds);

// When a temporary map was built, seconds.
struct TimeSpan {
  double start_s = 0.0;
  double end_s = 0.0;
  // Whether the spans overlap or lie less than `gap_s` apart.
  bool Near(const TimeSpan& o, double gap_s) const {
    return start_s < o.end_s + gap_s && o.start_s < end_s + gap_s;
  }
  // Whether they lie at least `min_gap_s` and at most `max_gap_s` apart (either order).
  bool Apart(const TimeSpan& o, double min_gap_s, double max_gap_s) const {
    return !Near(o, min_gap_s) && Near(o, max_gap_s);
  }
  double middle_s() const { return 0.5 * (start_s + end_s); }
};

// A cell seen occupied where nothing was, not yet an obstacle.
// Its watch runs from the end of the first map to last_seen_end_s.
struct Candidate {
  TimeSpan first;              // the map that saw it first (or that renewed it)
  double last_seen_end_s = 0;  // the end of the last map of its watch
  static Candidate SeenBy(const TimeSpan& span) { return {span, span.end_s}; }
};

// What the merge reads of the current map.
struct MergeInputs {
  const std::vector<uint8_t>* addable = nullptr;             // AddableCells of the static map
  const std::vector<uint8_t>* wall_distance = nullptr;       // WallDistances; null: no offset guard
  const std::vector<uint8_t>* semi_static = nullptr;         // per cell, 1: a semi-static obstacle
  const std::map<int64_t, Candidate>* candidates = nullptr;  // cell -> its sightings
  const std::vector<uint8_t>* candidate_mask = nullptr;      // per cell, 1: a candidate
  // Per cell, the end of the map whose evidence last added or removed it, s. Optional (null:
  // every map counts as newer).
  const std::vector<double>* changed_at_s = nullptr;
};

struct MergePlan {
  core::CellWindow dirty;           // bounding box of the changes; empty when there are none
  std::vector<CellChange> changes;  // ascending cell index
  int added = 0;
  int removed = 0;
  int candidates = 0;  // new (or renewed) candidates
  int watched = 0;     // candidates whose watch this map continued
  int dropped = 0;     // candidates seen free
};

// `span`: when the temporary map whose evidence this is was built. Maps arrive out of time
// order (a lossy link resends tiles for seconds; a vehicle back in range sends what it kept),
// so evidence older than a cell's last change does not undo it: a map that ended before the
// map that added a pallet saw the place free, and must not remove the pallet (nor re-add one
// taken away since). Nor does it drop a candidate a later map saw.
MergePlan PlanMerge(const PlacedEvidence& evidence, const TimeSpan& span, const MergeInputs& inputs,
                    const MergeOptions& options);

}  // namespace fleetmap::aggregator
