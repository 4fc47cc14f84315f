// One line of the change history: what a merge changed, where, when and seen by whom.
#pragma once

#include <string>

#include "aggregator/merge_commit.h"
#include "core/map/grid_geometry.h"

namespace fleetmap::ops::mapctl {

// An axis-aligned box in the map frame, metres.
struct BoxM {
  double x0_m = 0.0;
  double y0_m = 0.0;
  double x1_m = 0.0;
  double y1_m = 0.0;
};

struct MergeSummary {
  uint64_t version = 0;
  double merged_s = 0.0;  // the aggregator's clock when it merged
  std::string vehicle_id;
  int32_t tempmap_sequence = 0;
  int added = 0;               // cells that became semi-static obstacles
  int removed = 0;             // semi-static obstacles seen gone
  int candidates = 0;          // cells seen occupied once (not yet in the map)
  int candidates_dropped = 0;  // candidates seen free again
  bool has_box = false;        // false: the merge changed no cell
  BoxM box;  // the changed cells (every kind), their whole extent in the map frame
};

MergeSummary Summarize(const aggregator::MergeCommit& commit, const core::GridGeometry& geometry);

// "version merged_s vehicle seq added removed candidates dropped x0 y0 x1 y1"; a merge
// without cells prints "-" for the box.
std::string HistoryHeader();
std::string FormatSummary(const MergeSummary& s);

}  // namespace fleetmap::ops::mapctl
