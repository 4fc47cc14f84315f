#include "aggregator/current_map_store.h"

#include <algorithm>
#include <limits>
#include <string>

namespace fleetmap::aggregator {

core::Status StoreOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(tiles.Validate());
  FLEETMAP_RETURN_IF_ERROR(thresholds.Validate());
  if (retained_deltas < 0) return core::InvalidArgument("store.retained_deltas must be >= 0");
  return core::OkStatus();
}

CurrentMapStore::CurrentMapStore(core::OccupancyGrid static_map, const StoreOptions& options)
    : options_(options),
      static_map_(std::move(static_map)),
      current_(static_map_),
      semi_static_(static_cast<size_t>(static_map_.geometry().num_cells()), 0),
      static_occupied_(semi_static_.size(), 0),
      candidate_mask_(semi_static_.size(), 0),
      changed_at_s_(semi_static_.size(), -std::numeric_limits<double>::infinity()),
      layout_(static_map_.geometry(), options.tiles.tile_size_cells),
      tile_versions_(static_cast<size_t>(layout_.num_tiles()), 0) {
  const core::TriStateClassifier classify(options.thresholds);
  for (size_t i = 0; i < static_occupied_.size(); ++i)
    static_occupied_[i] = classify(static_map_.cells()[i]) == core::CellState::kOccupied;
}

uint64_t CurrentMapStore::TileVersion(const core::TileIndex& tile) const {
  return tile_versions_[static_cast<size_t>(layout_.Linear(tile))];
}

core::Status CurrentMapStore::Check(const MergeCommit& commit) const {
  const std::string where = "commit of version " + std::to_string(commit.version) + ": ";
  if (commit.version != version_ + 1) {
    return core::FailedPrecondition(where + "the current map is at version " +
                                    std::to_string(version_));
  }
  const int64_t n = static_map_.geometry().num_cells();
  for (size_t k = 0; k < commit.changes.size(); ++k) {
    const CellChange& c = commit.changes[k];
    if (c.cell < 0 || c.cell >= n || (k > 0 && c.cell <= commit.changes[k - 1].cell))
      return core::FailedPrecondition(where + "cell index out of range or out of order");
    if (static_occupied_[static_cast<size_t>(c.cell)])
      return core::FailedPrecondition(where + "touches a static cell");
    if (!Fits(c)) return core::FailedPrecondition(where + "a change does not fit the cell's state");
  }
  return core::OkStatus();
}

bool CurrentMapStore::Fits(const CellChange& c) const {
  const bool semi = semi_static_[static_cast<size_t>(c.cell)] != 0;
  const bool candidate = candidate_mask_[static_cast<size_t>(c.cell)] != 0;
  switch (c.kind) {
    case CellChangeKind::kAdded:
      return !semi;
    case CellChangeKind::kRemoved:
      return semi;
    case CellChangeKind::kCandidate:  // new, or renewed by a later sighting
      return !semi;
    case CellChangeKind::kCandidateDropped:
    case CellChangeKind::kCandidateWatched:
      return candidate;
  }
  return false;
}

void CurrentMapStore::ApplyChange(const CellChange& c, const TimeSpan& span) {
  const size_t i = static_cast<size_t>(c.cell);
  switch (c.kind) {
    case CellChangeKind::kAdded:
      semi_static_[i] = 1;
      current_.mutable_cells()[i] = current_.CanonicalLogOdds(core::CellState::kOccupied);
      candidates_.erase(c.cell);
      candidate_mask_[i] = 0;
      changed_at_s_[i] = span.end_s;
      break;
    case CellChangeKind::kRemoved:
      semi_static_[i] = 0;
      current_.mutable_cells()[i] = static_map_.cells()[i];
      changed_at_s_[i] = span.end_s;
      break;
    case CellChangeKind::kCandidate:
      candidates_[c.cell] = Candidate::SeenBy(span);
      candidate_mask_[i] = 1;
      break;
    case CellChangeKind::kCandidateWatched: {
      Candidate& candidate = candidates_.at(c.cell);
      candidate.last_seen_end_s = std::max(candidate.last_seen_end_s, span.end_s);
      break;
    }
    case CellChangeKind::kCandidateDropped:
      candidates_.erase(c.cell);
      candidate_mask_[i] = 0;
      break;
  }
}

std::vector<int> CurrentMapStore::TouchedTiles(const std::vector<CellChange>& changes) const {
  const int w = static_map_.geometry().width(), size = options_.tiles.tile_size_cells;
  std::vector<int> tiles;
  for (const CellChange& c : changes) {
    if (c.kind != CellChangeKind::kAdded && c.kind != CellChangeKind::kRemoved) continue;
    const int x = static_cast<int>(c.cell % w), y = static_cast<int>(c.cell / w);
    tiles.push_back(layout_.Linear({x / size, y / size}));
  }
  std::sort(tiles.begin(), tiles.end());
  tiles.erase(std::unique(tiles.begin(), tiles.end()), tiles.end());
  return tiles;
}

core::Result<MapDelta> CurrentMapStore::Apply(MergeCommit commit) {
  FLEETMAP_RETURN_IF_ERROR(Check(commit));
  const TimeSpan span{commit.source.tempmap_start_s, commit.source.tempmap_end_s};
  for (const CellChange& c : commit.changes) ApplyChange(c, span);
  version_ = commit.version;
  MapDelta delta{version_ - 1, version_, {}};
  for (int t : TouchedTiles(commit.changes)) {
    tile_versions_[static_cast<size_t>(t)] = version_;
    const core::TileIndex index = layout_.FromLinear(t);
    delta.tiles.push_back(
        {index, core::EncodeWindow(current_, layout_.Window(index), options_.tiles.codec)});
  }
  deltas_.push_back(delta);
  while (deltas_.size() > static_cast<size_t>(options_.retained_deltas)) deltas_.pop_front();
  provenance_.Record(std::move(commit));
  return delta;
}

core::Result<MapDelta> CurrentMapStore::Delta(uint64_t from_version) const {
  for (const MapDelta& d : deltas_)
    if (d.from_version == from_version) return d;
  return core::NotFound("delta from version " + std::to_string(from_version) +
                        " is not retained (current version " + std::to_string(version_) + ")");
}

MapDelta CurrentMapStore::DeltaSince(uint64_t version) const {
  MapDelta delta{version, version_, {}};
  for (int t = 0; t < layout_.num_tiles(); ++t) {
    if (tile_versions_[static_cast<size_t>(t)] <= version) continue;
    const core::TileIndex index = layout_.FromLinear(t);
    delta.tiles.push_back(
        {index, core::EncodeWindow(current_, layout_.Window(index), options_.tiles.codec)});
  }
  return delta;
}

MapDelta CurrentMapStore::Keyframe() const {
  return {0, version_, core::EncodeAllTiles(current_, options_.tiles)};
}

}  // namespace fleetmap::aggregator
