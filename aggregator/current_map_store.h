// The versioned current map: the static map plus every merged change. The version grows by
// one per accepted merge; the map is cut into codec tiles (core/codec/tile_delta.h), each with the
// version that last changed it, so any vehicle can be brought up to date from the version it
// has; the delta from v to v+1 of the latest merges is kept ready to send, and a keyframe
// (every tile) is encoded on request. The store checks every commit before it applies it,
// including commits replayed from disk, and applies all of a commit or nothing.
#pragma once

#include <deque>
#include <vector>

#include "aggregator/merge.h"
#include "aggregator/merge_commit.h"
#include "aggregator/provenance.h"
#include "core/codec/tile_delta.h"

namespace fleetmap::aggregator {

struct StoreOptions {
  core::TileOptions tiles;               // tile size and codec of deltas and keyframes
  int retained_deltas = 64;              // deltas v -> v+1 kept for resending, >= 0
  core::OccupancyThresholds thresholds;  // classify the static map's cells
  core::Status Validate() const;
};

struct MapDelta {
  uint64_t from_version = 0;
  uint64_t to_version = 0;
  std::vector<core::EncodedTile> tiles;  // the tiles that differ, encoded from to_version
};

class CurrentMapStore {
 public:
  // The static map's geometry must be valid (validate outside data first).
  CurrentMapStore(core::OccupancyGrid static_map, const StoreOptions& options);

  uint64_t version() const { return version_; }
  const core::OccupancyGrid& static_map() const { return static_map_; }
  const core::OccupancyGrid& current_map() const { return current_; }
  // Per cell: 1 where the current map holds a semi-static obstacle.
  const std::vector<uint8_t>& semi_static() const { return semi_static_; }
  // Cells seen occupied once, waiting for confirmation, with the span of the map that saw them
  // (last).
  const std::map<int64_t, Candidate>& candidates() const { return candidates_; }
  const std::vector<uint8_t>& candidate_mask() const { return candidate_mask_; }
  // Per cell: the end of the temporary map whose evidence last added or removed it, s
  // (-infinity if none did). Rebuilt by replaying the commits, like everything else here.
  const std::vector<double>& changed_at_s() const { return changed_at_s_; }
  const ProvenanceLog& provenance() const { return provenance_; }
  const core::TileLayout& layout() const { return layout_; }
  uint64_t TileVersion(const core::TileIndex& tile) const;

  // FailedPrecondition unless the commit continues this map: version() + 1, cells inside the
  // map, no static cell touched, added cells not yet semi-static, removed cells semi-static,
  // candidates (new, or renewed by a later sighting) not semi-static, dropped candidates
  // candidates.
  core::Status Check(const MergeCommit& commit) const;
  // Check, then apply: the map, tile versions, the retained delta and the provenance.
  // Returns the delta from version() - 1 to version().
  core::Result<MapDelta> Apply(MergeCommit commit);

  // The delta from `from_version` to from_version + 1, if still retained (NotFound if not).
  core::Result<MapDelta> Delta(uint64_t from_version) const;
  // Every tile changed after `version`: brings a map of any older version up to date.
  MapDelta DeltaSince(uint64_t version) const;
  // Every tile of the current map.
  MapDelta Keyframe() const;

 private:
  std::vector<int> TouchedTiles(const std::vector<CellChange>& changes) const;
  bool Fits(const CellChange& change) const;
  void ApplyChange(const CellChange& change, const TimeSpan& span);

  StoreOptions options_;
  core::OccupancyGrid static_map_;
  core::OccupancyGrid current_;
  std::vector<uint8_t> semi_static_;
  std::vector<uint8_t> static_occupied_;
  std::map<int64_t, Candidate> candidates_;
  std::vector<uint8_t> candidate_mask_;  // per cell, 1 for a key of candidates_
  std::vector<double> changed_at_s_;
  core::TileLayout layout_;
  std::vector<uint64_t> tile_versions_;
  std::deque<MapDelta> deltas_;  // the latest retained_deltas, oldest first
  ProvenanceLog provenance_;
  uint64_t version_ = 0;
};

}  // namespace fleetmap::aggregator
