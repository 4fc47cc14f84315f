#include "ops/mapctl/merge_summary.h"

#include <algorithm>
#include <cstdio>

namespace fleetmap::ops::mapctl {
namespace {

using aggregator::CellChangeKind;

void Count(CellChangeKind kind, MergeSummary& s) {
  switch (kind) {
    case CellChangeKind::kAdded:
      ++s.added;
      break;
    case CellChangeKind::kRemoved:
      ++s.removed;
      break;
    case CellChangeKind::kCandidate:
      ++s.candidates;
      break;
    case CellChangeKind::kCandidateDropped:
      ++s.candidates_dropped;
      break;
    case CellChangeKind::kCandidateWatched:  // seen again: neither the map nor the count change
      break;
  }
}

// Grows the box by the four corners of a cell (the map frame may be rotated).
void Extend(const core::GridGeometry& g, int64_t cell, MergeSummary& s) {
  const int x = static_cast<int>(cell % g.width()), y = static_cast<int>(cell / g.width());
  const double r = g.resolution_m();
  for (int corner = 0; corner < 4; ++corner) {
    const Eigen::Vector2d p =
        g.origin().Apply(Eigen::Vector2d(x + (corner & 1), y + (corner >> 1)) * r);
    if (!s.has_box) {
      s.box = {p.x(), p.y(), p.x(), p.y()};
      s.has_box = true;
    }
    s.box.x0_m = std::min(s.box.x0_m, p.x());
    s.box.y0_m = std::min(s.box.y0_m, p.y());
    s.box.x1_m = std::max(s.box.x1_m, p.x());
    s.box.y1_m = std::max(s.box.y1_m, p.y());
  }
}

}  // namespace

MergeSummary Summarize(const aggregator::MergeCommit& commit, const core::GridGeometry& geometry) {
  MergeSummary s;
  s.version = commit.version;
  s.merged_s = commit.source.merged_s;
  s.vehicle_id = commit.source.vehicle_id;
  s.tempmap_sequence = commit.source.tempmap_sequence;
  for (const aggregator::CellChange& c : commit.changes) {
    Count(c.kind, s);
    Extend(geometry, c.cell, s);
  }
  return s;
}

std::string HistoryHeader() {
  return "version merged_s vehicle tempmap added removed candidates dropped x0_m y0_m x1_m y1_m";
}

std::string FormatSummary(const MergeSummary& s) {
  char line[512];
  std::snprintf(line, sizeof(line), "%llu %.3f %s %d %d %d %d %d", (unsigned long long)s.version,
                s.merged_s, s.vehicle_id.c_str(), s.tempmap_sequence, s.added, s.removed,
                s.candidates, s.candidates_dropped);
  std::string out = line;
  if (!s.has_box) return out + " - - - -";
  std::snprintf(line, sizeof(line), " %.2f %.2f %.2f %.2f", s.box.x0_m, s.box.y0_m, s.box.x1_m,
                s.box.y1_m);
  return out + line;
}

}  // namespace fleetmap::ops::mapctl
