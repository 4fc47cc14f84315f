// One accepted merge as it is versioned, journaled and replayed: the cells it changed and
// who saw them. Replaying commits in order rebuilds the current map exactly (no alignment or
// floating point is redone), which is what makes restarts and deterministic runs
// byte-identical. Payload layout (little-endian), used by the journal and the snapshot:
//
//   u8  format version (kCommitFormatVersion)
//   u64 map version this commit creates
//   u32 n, n bytes   vehicle id (1..kMaxVehicleIdBytes)
//   i32 temporary map sequence
//   f64 x3           temporary map start, end; time of the merge (seconds)
//   f64 x3           correction x, y (m), theta (rad)
//   u32 count        cell changes, then per change: u32 cell index (row-major), u8 kind
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "core/result.h"

namespace fleetmap::aggregator {

constexpr uint8_t kCommitFormatVersion = 1;
constexpr size_t kMaxVehicleIdBytes = 256;

enum class CellChangeKind : uint8_t {
  kAdded = 1,    // a semi-static obstacle appeared where the static map is free
  kRemoved = 2,  // a semi-static obstacle was seen gone
  // Seen occupied once: a candidate until a temporary map of another time confirms it
  // (merge.h, MergeOptions::confirmations); seen again too late for that, it is renewed with
  // the later map's time. The map's cells do not change.
  kCandidate = 3,
  kCandidateDropped = 4,  // a candidate seen free again: it was passing by
  // A candidate seen occupied again by a map that continues its watch (merge.h).
  kCandidateWatched = 5,
};
bool IsValidCellChangeKind(uint8_t code);
const char* CellChangeKindName(CellChangeKind kind);

struct CellChange {
  int64_t cell = 0;  // row-major index into the static map
  CellChangeKind kind = CellChangeKind::kAdded;
  bool operator==(const CellChange& o) const { return cell == o.cell && kind == o.kind; }
};

// Who saw a change and when.
struct ChangeSource {
  std::string vehicle_id;
  int32_t tempmap_sequence = 0;
  double tempmap_start_s = 0.0;
  double tempmap_end_s = 0.0;
  double merged_s = 0.0;  // when the aggregator merged it (time passed in by the caller)
};

struct MergeCommit {
  uint64_t version = 0;  // the map version this commit creates
  ChangeSource source;
  core::Pose2 correction;           // applied to the anchor, for the record
  std::vector<CellChange> changes;  // ascending cell index, each cell at most once
};

std::vector<uint8_t> EncodeCommit(const MergeCommit& commit);
// DataLoss for truncated or malformed payloads, Unimplemented for a newer format version.
core::Result<MergeCommit> DecodeCommit(const uint8_t* data, size_t size);

}  // namespace fleetmap::aggregator
