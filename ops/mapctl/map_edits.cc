#include "ops/mapctl/map_edits.h"

#include <algorithm>
#include <cmath>

namespace fleetmap::ops::mapctl {
namespace {

using aggregator::CellChange;
using aggregator::CellChangeKind;
using aggregator::CurrentMapStore;

bool Inside(const BoxM& box, const Eigen::Vector2d& p) {
  return p.x() >= std::min(box.x0_m, box.x1_m) && p.x() <= std::max(box.x0_m, box.x1_m) &&
         p.y() >= std::min(box.y0_m, box.y1_m) && p.y() <= std::max(box.y0_m, box.y1_m);
}

core::CellIndex CellOf(const core::GridGeometry& g, int64_t cell) {
  return {static_cast<int>(cell % g.width()), static_cast<int>(cell / g.width())};
}

// The latest change of a cell in the store's history (a semi-static cell has one).
const aggregator::CellEvent* Latest(const std::vector<aggregator::CellEvent>& events) {
  return events.empty() ? nullptr : &events.back();
}

}  // namespace

aggregator::MergeCommit ResetRegionCommit(const CurrentMapStore& store, const BoxM& box,
                                          double now_s) {
  aggregator::MergeCommit commit;
  commit.version = store.version() + 1;
  commit.source.vehicle_id = kEditVehicleId;
  commit.source.tempmap_start_s = commit.source.tempmap_end_s = commit.source.merged_s = now_s;
  const core::GridGeometry& g = store.static_map().geometry();
  for (int64_t cell = 0; cell < g.num_cells(); ++cell) {
    const size_t i = static_cast<size_t>(cell);
    const bool semi = store.semi_static()[i] != 0, candidate = store.candidate_mask()[i] != 0;
    if ((!semi && !candidate) || !Inside(box, g.CellCenter(CellOf(g, cell)))) continue;
    commit.changes.push_back(
        {cell, semi ? CellChangeKind::kRemoved : CellChangeKind::kCandidateDropped});
  }
  return commit;
}

core::Status PromoteOptions::Validate() const {
  if (!since_version && !min_age_s)
    return core::InvalidArgument("promote needs --since-version or --older-than");
  if (min_age_s && !(*min_age_s >= 0.0 && std::isfinite(*min_age_s)))
    return core::InvalidArgument("--older-than must be a finite number of seconds >= 0");
  if (!std::isfinite(now_s)) return core::InvalidArgument("--now must be finite");
  return core::OkStatus();
}

std::vector<int64_t> StandingCells(const CurrentMapStore& store, const PromoteOptions& options) {
  std::vector<int64_t> cells;
  for (size_t i = 0; i < store.semi_static().size(); ++i) {
    if (!store.semi_static()[i]) continue;
    const auto events = store.provenance().HistoryOf(static_cast<int64_t>(i));
    const aggregator::CellEvent* added = Latest(events);
    if (!added) continue;  // not reachable: a semi-static cell was added by a commit
    if (options.since_version && added->version > *options.since_version) continue;
    if (options.min_age_s && options.now_s - added->source->merged_s < *options.min_age_s) continue;
    cells.push_back(static_cast<int64_t>(i));
  }
  return cells;
}

Promotion Promote(const CurrentMapStore& store, const std::vector<int64_t>& cells) {
  Promotion p{store.static_map(), {}};
  const core::GridGeometry& g = p.static_map.geometry();
  for (int64_t cell : cells) p.static_map.SetState(CellOf(g, cell), core::CellState::kOccupied);
  for (aggregator::MergeCommit commit : store.provenance().commits()) {
    auto& changes = commit.changes;
    changes.erase(std::remove_if(changes.begin(), changes.end(),
                                 [&cells](const CellChange& c) {
                                   return std::binary_search(cells.begin(), cells.end(), c.cell);
                                 }),
                  changes.end());
    p.commits.push_back(std::move(commit));
  }
  return p;
}

}  // namespace fleetmap::ops::mapctl
