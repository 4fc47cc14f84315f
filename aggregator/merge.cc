#include "aggregator/merge.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <optional>

namespace fleetmap::aggregator {
namespace {

void Grow(core::CellWindow& w, int x, int y) {
  if (w.width == 0) {
    w = {x, y, 1, 1};
    return;
  }
  const int x1 = std::max(w.x0 + w.width, x + 1), y1 = std::max(w.y0 + w.height, y + 1);
  w.x0 = std::min(w.x0, x), w.y0 = std::min(w.y0, y);
  w.width = x1 - w.x0, w.height = y1 - w.y0;
}

// Decides every cell of the evidence window (phase 2 of the merge), reading the current map
// through `in` and writing nothing but the plan.
class Planner {
 public:
  Planner(const PlacedEvidence& e, const TimeSpan& span, const MergeInputs& in,
          const MergeOptions& o)
      : e_(e),
        w_(e.window),
        span_(span),
        in_(in),
        o_(o),
        cells_(MergeCellsFor(o, e.resolution_m)),
        wall_clearance_(WallClearance()) {}

  MergePlan Run() {
    std::vector<std::optional<CellChangeKind>> decided(static_cast<size_t>(w_.num_cells()));
    for (int y = w_.y0; y < w_.y0 + w_.height; ++y)
      for (int x = w_.x0; x < w_.x0 + w_.width; ++x) decided[Local(x, y)] = Decide(x, y);
    if (o_.confirmations > 1) GrowConfirmed(decided);
    return Collect(decided);
  }

 private:
  size_t Local(int x, int y) const {
    return static_cast<size_t>(y - w_.y0) * w_.width + (x - w_.x0);
  }
  size_t Global(int x, int y) const { return static_cast<size_t>(y) * e_.map_width + x; }
  bool InWindow(int x, int y) const {
    return x >= w_.x0 && y >= w_.y0 && x < w_.x0 + w_.width && y < w_.y0 + w_.height;
  }
  bool Semi(int x, int y) const { return (*in_.semi_static)[Global(x, y)] != 0; }
  bool Candidate(int x, int y) const { return (*in_.candidate_mask)[Global(x, y)] != 0; }
  bool Strong(int x, int y) const { return e_.at({x, y}) >= o_.add_min_log_odds; }

  // Calls fn(nx, ny) for the cells within r of (x, y) inside the window, not (x, y) itself,
  // until it returns true; returns whether it did.
  template <typename Fn>
  bool AnyNear(int x, int y, int r, Fn fn) const {
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx)
        if ((dx || dy) && InWindow(x + dx, y + dy) && fn(x + dx, y + dy)) return true;
    return false;
  }

  // How close to a static wall this map adds nothing: static_clearance_m, or farther where
  // this map draws the walls farther off (see MergeOptions::wall_offset_window_m).
  int WallClearance() const {
    const int base = cells_.static_clearance;
    const int window = CellsFor(o_.wall_offset_window_m, e_.resolution_m);
    if (!in_.wall_distance || window <= base) return base;
    std::vector<int64_t> hits_at(static_cast<size_t>(window) + 1, 0);
    int64_t hits = 0;
    for (int y = w_.y0; y < w_.y0 + w_.height; ++y)
      for (int x = w_.x0; x < w_.x0 + w_.width; ++x) {
        const int d = (*in_.wall_distance)[Global(x, y)];
        if (d <= window && Strong(x, y)) ++hits_at[static_cast<size_t>(d)], ++hits;
      }
    if (hits < kMinWallHits) return base;
    int64_t within = 0;
    for (int d = 0; d <= window; ++d)
      if ((within += hits_at[static_cast<size_t>(d)]) * 10 >= hits * 9) return std::max(base, d);
    return window;
  }
  // Fewer hits near walls say nothing about how far off the map draws them.
  static constexpr int64_t kMinWallHits = 20;

  // Occupied in this map where an obstacle may be, and not an isolated return.
  bool Seen(int x, int y) const {
    if (!Strong(x, y) || !(*in_.addable)[Global(x, y)]) return false;
    if (in_.wall_distance && (*in_.wall_distance)[Global(x, y)] <= wall_clearance_) return false;
    int neighbours = 0;
    AnyNear(x, y, 1, [&](int nx, int ny) {
      neighbours += Strong(nx, ny);
      return false;
    });
    return neighbours >= o_.min_occupied_neighbours;
  }

  // A candidate confirms if seen by a map confirm_min_gap_s to confirm_max_gap_s away in time
  // from this one, or if this map ends a watch of it that lasted confirm_min_gap_s.
  bool Confirms(int x, int y) const {
    if (!Candidate(x, y)) return false;
    const aggregator::Candidate& c = CandidateAt(x, y);
    return c.first.Apart(span_, o_.confirm_min_gap_s, o_.confirm_max_gap_s) ||
           (o_.confirm_by_watch && ContinuesWatch(c) &&
            span_.middle_s() - c.first.end_s >= o_.confirm_min_gap_s);
  }
  const aggregator::Candidate& CandidateAt(int x, int y) const {
    return in_.candidates->at(static_cast<int64_t>(Global(x, y)));
  }
  // Whether this map starts when the last map that saw the candidate ended (or overlaps it:
  // another vehicle watching at the same time) and ends later.
  bool ContinuesWatch(const aggregator::Candidate& c) const {
    return span_.start_s <= c.last_seen_end_s + o_.watch_join_s && span_.end_s > c.last_seen_end_s;
  }
  // A candidate at or near (x, y) that confirms.
  bool EarlierSightingNear(int x, int y) const {
    auto confirms = [&](int nx, int ny) { return Confirms(nx, ny); };
    return confirms(x, y) || AnyNear(x, y, cells_.confirm_radius, confirms);
  }
  // A candidate that can no longer be confirmed or dropped by a map this late.
  bool Stale(int x, int y) const {
    return Candidate(x, y) && !CandidateAt(x, y).first.Near(span_, o_.confirm_max_gap_s);
  }

  // A semi-static cell is removed when seen free, with nothing occupied next to it and every
  // semi-static neighbour seen free as well (a map a little off may see a strip of a pallet
  // that is still there free; one taken away leaves its whole neighbourhood free).
  std::optional<CellChangeKind> DecideSemiStatic(int x, int y) const {
    const int r = cells_.removal_clearance;
    if (e_.at({x, y}) > o_.remove_max_log_odds) return std::nullopt;
    const bool blocked = AnyNear(x, y, r, [&](int nx, int ny) {
      return Strong(nx, ny) || (Semi(nx, ny) && e_.at({nx, ny}) >= 0.0f);
    });
    return blocked ? std::nullopt : std::optional(CellChangeKind::kRemoved);
  }

  std::optional<CellChangeKind> Decide(int x, int y) const {
    if (Semi(x, y)) return DecideSemiStatic(x, y);
    const bool candidate = Candidate(x, y);
    if (candidate && e_.at({x, y}) <= o_.remove_max_log_odds)
      return CellChangeKind::kCandidateDropped;
    const bool seen = Seen(x, y);
    if (o_.confirmations <= 1) return seen ? std::optional(CellChangeKind::kAdded) : std::nullopt;
    if (seen && EarlierSightingNear(x, y)) return CellChangeKind::kAdded;
    // A candidate whose neighbourhood this map sees occupied at another time.
    const bool neighbour_strong =
        candidate &&
        AnyNear(x, y, cells_.confirm_radius, [&](int nx, int ny) { return Strong(nx, ny); });
    if (neighbour_strong && EarlierSightingNear(x, y)) return CellChangeKind::kAdded;
    // ... or at the same time as the last map that saw it: its watch goes on.
    if (o_.confirm_by_watch && candidate && (Strong(x, y) || neighbour_strong) &&
        ContinuesWatch(CandidateAt(x, y)))
      return CellChangeKind::kCandidateWatched;
    // First seen, or seen again too late to confirm: a candidate from this map on.
    if (seen && (!candidate || Stale(x, y))) return CellChangeKind::kCandidate;
    return std::nullopt;
  }

  // Cells this map sees occupied that connect (through other such cells) to an obstacle
  // of the current map that this map sees as well belong to it: another face of the same
  // pallet, seen once. They are added too. (Only obstacles confirmed before: a person who
  // happened to stand at the same place at both sightings does not drag the rest of what
  // this map saw of him in. Only obstacles seen now: a forklift that stops where a person
  // was wrongly mapped is no face of it.)
  void GrowConfirmed(std::vector<std::optional<CellChangeKind>>& decided) const {
    std::vector<std::pair<int, int>> stack;
    for (int y = w_.y0; y < w_.y0 + w_.height; ++y)
      for (int x = w_.x0; x < w_.x0 + w_.width; ++x)
        if (Semi(x, y) && Strong(x, y)) stack.emplace_back(x, y);
    while (!stack.empty()) {
      const auto [x, y] = stack.back();
      stack.pop_back();
      AnyNear(x, y, cells_.confirm_radius, [&](int nx, int ny) {
        auto& d = decided[Local(nx, ny)];
        if (Semi(nx, ny) || d == CellChangeKind::kAdded || !Seen(nx, ny)) return false;
        d = CellChangeKind::kAdded;
        stack.emplace_back(nx, ny);
        return false;
      });
    }
  }

  // Whether this map's evidence is older than what last decided the cell (see PlanMerge).
  bool Outdated(int x, int y, CellChangeKind kind) const {
    switch (kind) {
      case CellChangeKind::kAdded:
      case CellChangeKind::kRemoved:
        return in_.changed_at_s && span_.end_s < (*in_.changed_at_s)[Global(x, y)];
      case CellChangeKind::kCandidateDropped:
        return span_.end_s < CandidateAt(x, y).last_seen_end_s;
      case CellChangeKind::kCandidate:
      case CellChangeKind::kCandidateWatched:
        return false;
    }
    return false;
  }

  MergePlan Collect(const std::vector<std::optional<CellChangeKind>>& decided) const {
    MergePlan plan;
    for (int y = w_.y0; y < w_.y0 + w_.height; ++y) {
      for (int x = w_.x0; x < w_.x0 + w_.width; ++x) {
        const auto kind = decided[Local(x, y)];
        if (!kind || Outdated(x, y, *kind)) continue;
        plan.changes.push_back({static_cast<int64_t>(Global(x, y)), *kind});
        switch (*kind) {
          case CellChangeKind::kAdded:
            ++plan.added, Grow(plan.dirty, x, y);
            break;
          case CellChangeKind::kRemoved:
            ++plan.removed, Grow(plan.dirty, x, y);
            break;
          case CellChangeKind::kCandidate:
            ++plan.candidates;
            break;
          case CellChangeKind::kCandidateDropped:
            ++plan.dropped;
            break;
          case CellChangeKind::kCandidateWatched:
            ++plan.watched;
            break;
        }
      }
    }
    return plan;
  }

  const PlacedEvidence& e_;
  const core::CellWindow& w_;
  TimeSpan span_;
  const MergeInputs& in_;
  const MergeOptions& o_;
  const MergeCells cells_;
  const int wall_clearance_;
};

}  // namespace

core::Status MergeOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(thresholds.Validate());
  if (!(add_min_log_odds > 0)) return core::InvalidArgument("merge.add_min_log_odds must be > 0");
  if (!(remove_max_log_odds < 0))
    return core::InvalidArgument("merge.remove_max_log_odds must be < 0");
  if (!(static_clearance_m >= 0 && static_clearance_m <= 0.5))
    return core::InvalidArgument("merge.static_clearance_m must be in [0, 0.5] m");
  if (!(wall_offset_window_m >= 0 && wall_offset_window_m <= 0.5))
    return core::InvalidArgument("merge.wall_offset_window_m must be in [0, 0.5] m");
  if (!(held_wall_clearance_m >= 0 && held_wall_clearance_m <= 0.5))
    return core::InvalidArgument("merge.held_wall_clearance_m must be in [0, 0.5] m");
  if (min_occupied_neighbours < 0 || min_occupied_neighbours > 8)
    return core::InvalidArgument("merge.min_occupied_neighbours must be in [0, 8]");
  if (!(removal_clearance_m >= 0 && removal_clearance_m <= 0.5))
    return core::InvalidArgument("merge.removal_clearance_m must be in [0, 0.5] m");
  if (confirmations < 1 || confirmations > 2)
    return core::InvalidArgument("merge.confirmations must be 1 or 2");
  if (!(confirm_radius_m >= 0 && confirm_radius_m <= 0.3))
    return core::InvalidArgument("merge.confirm_radius_m must be in [0, 0.3] m");
  if (!(confirm_min_gap_s >= 0))
    return core::InvalidArgument("merge.confirm_min_gap_s must be >= 0");
  if (!(watch_join_s >= 0)) return core::InvalidArgument("merge.watch_join_s must be >= 0");
  if (!(confirm_max_gap_s > confirm_min_gap_s))
    return core::InvalidArgument("merge.confirm_max_gap_s must be > confirm_min_gap_s");
  return core::OkStatus();
}

int CellsFor(double distance_m, double resolution_m) {
  if (!(distance_m > 0) || !(resolution_m > 0)) return 0;
  return std::max(1, static_cast<int>(std::lround(distance_m / resolution_m)));
}

MergeCells MergeCellsFor(const MergeOptions& o, double resolution_m) {
  return {CellsFor(o.static_clearance_m, resolution_m),
          CellsFor(o.removal_clearance_m, resolution_m),
          CellsFor(o.confirm_radius_m, resolution_m)};
}

std::vector<uint8_t> AddableCells(const core::OccupancyGrid& static_map,
                                  const MergeOptions& options) {
  return AddableCells(static_map, options, WallDistances(static_map, options.thresholds));
}

std::vector<uint8_t> AddableCells(const core::OccupancyGrid& static_map,
                                  const MergeOptions& options,
                                  const std::vector<uint8_t>& wall_distance) {
  const core::TriStateClassifier classify(options.thresholds);
  const int r = CellsFor(options.static_clearance_m, static_map.geometry().resolution_m());
  const std::vector<float>& cells = static_map.cells();
  std::vector<uint8_t> addable(cells.size(), 0);
  for (size_t i = 0; i < cells.size(); ++i)
    addable[i] = classify(cells[i]) == core::CellState::kFree && wall_distance[i] > r;
  return addable;
}

std::vector<uint8_t> WallDistances(const core::OccupancyGrid& static_map,
                                   const core::OccupancyThresholds& thresholds) {
  const core::TriStateClassifier classify(thresholds);
  const int w = static_map.geometry().width(), h = static_map.geometry().height();
  const std::vector<float>& cells = static_map.cells();
  std::vector<uint8_t> d(cells.size(), 255);
  for (size_t i = 0; i < cells.size(); ++i)
    if (classify(cells[i]) == core::CellState::kOccupied) d[i] = 0;
  // The chessboard distance transform: two passes over the 8-neighbourhood.
  auto relax = [&](size_t i, int x, int y, int dx, int dy) {
    const int nx = x + dx, ny = y + dy;
    if (nx < 0 || ny < 0 || nx >= w || ny >= h) return;
    const uint8_t n = d[static_cast<size_t>(ny) * w + nx];
    if (n < 255 && n + 1 < d[i]) d[i] = static_cast<uint8_t>(n + 1);
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      relax(i, x, y, -1, -1), relax(i, x, y, 0, -1), relax(i, x, y, 1, -1), relax(i, x, y, -1, 0);
    }
  for (int y = h - 1; y >= 0; --y)
    for (int x = w - 1; x >= 0; --x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      relax(i, x, y, 1, 1), relax(i, x, y, 0, 1), relax(i, x, y, -1, 1), relax(i, x, y, 1, 0);
    }
  return d;
}

MergePlan PlanMerge(const PlacedEvidence& evidence, const TimeSpan& span, const MergeInputs& inputs,
                    const MergeOptions& options) {
  assert(inputs.addable && inputs.semi_static && inputs.candidates && inputs.candidate_mask);
  return Planner(evidence, span, inputs, options).Run();
}

}  // namespace fleetmap::aggregator
