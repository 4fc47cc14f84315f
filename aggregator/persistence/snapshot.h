// The snapshot of the current map: every accepted merge since the static map, so a restart
// rebuilds the same map, the same version, the same tile versions and the same history.
// Written atomically (core::WriteFileAtomically: temporary file, fsync, rename, fsync of
// the folder), so a crash leaves the old snapshot or the new one. Layout (little-endian):
//
//   "FMS1", u32 format version (kSnapshotFormatVersion)
//   u64 map version
//   u32 fingerprint of the static map it was made for (MapFingerprint)
//   u32 fingerprint of the current map at that version (checked after the rebuild)
//   u32 commit count, then per commit: u32 length, the commit payload (merge_commit.h)
//   u32 CRC-32 of every byte before it
#pragma once

#include <string>
#include <vector>

#include "aggregator/current_map_store.h"

namespace fleetmap::aggregator {

constexpr uint32_t kSnapshotFormatVersion = 1;

// CRC-32 over a grid's geometry (resolution, size, origin) and its cells' bytes.
uint32_t MapFingerprint(const core::OccupancyGrid& grid);

struct SnapshotContents {
  uint64_t version = 0;
  uint32_t static_fingerprint = 0;
  uint32_t map_fingerprint = 0;
  std::vector<MergeCommit> commits;
};

std::vector<uint8_t> EncodeSnapshot(const CurrentMapStore& store);
// DataLoss for a corrupt or truncated snapshot, Unimplemented for a newer format.
core::Result<SnapshotContents> DecodeSnapshot(const uint8_t* data, size_t size);

core::Status WriteSnapshot(const CurrentMapStore& store, const std::string& path);
// NotFound when there is no snapshot.
core::Result<SnapshotContents> ReadSnapshot(const std::string& path, int64_t max_bytes);

}  // namespace fleetmap::aggregator
