// Edits an operator makes to the map's history, as new states of the same kind the
// aggregator writes, so that it restarts from them like from its own:
//  - reset a region: one more commit (source "mapctl") that removes every semi-static
//    obstacle and drops every candidate in a box, so the region is the static map again;
//  - promote: obstacles standing long enough become part of the static map; every commit
//    loses its changes of those cells (so none touches a static cell) and keeps its version.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "aggregator/current_map_store.h"
#include "ops/mapctl/merge_summary.h"

namespace fleetmap::ops::mapctl {

constexpr const char* kEditVehicleId = "mapctl";  // the source of commits made by edits

// The commit of version store.version() + 1 that resets the cells whose centres lie in
// `box` (corners in any order). Its source is kEditVehicleId at `now_s`. It may hold no
// change (the region held none): applying it still makes a version.
aggregator::MergeCommit ResetRegionCommit(const aggregator::CurrentMapStore& store, const BoxM& box,
                                          double now_s);

// Which standing obstacles to promote: semi-static cells whose latest change (their
// addition) is at or before `since_version`, and/or merged at least `min_age_s` before
// `now_s`. With both set, a cell must meet both.
struct PromoteOptions {
  std::optional<uint64_t> since_version;
  std::optional<double> min_age_s;  // seconds, >= 0
  double now_s = 0.0;               // the aggregator's clock (merged_s) now
  core::Status Validate() const;
};

// Cell indices (ascending) of the obstacles PromoteOptions selects.
std::vector<int64_t> StandingCells(const aggregator::CurrentMapStore& store,
                                   const PromoteOptions& options);

struct Promotion {
  core::OccupancyGrid static_map;                // the old one with the cells occupied
  std::vector<aggregator::MergeCommit> commits;  // the history without those cells
};

// The static map and history after promoting `cells` (semi-static cells of `store`).
Promotion Promote(const aggregator::CurrentMapStore& store, const std::vector<int64_t>& cells);

}  // namespace fleetmap::ops::mapctl
