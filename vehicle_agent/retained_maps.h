// The temporary maps a vehicle keeps after the aggregator merged them, so that it can send
// them again if the aggregator loses them (a damaged state folder put right with
// `fleetmap-mapctl recover`, which then asks the fleet: docs/operations.md). The vehicles are
// the replicas of what the aggregator acknowledged. Bounded twice: a map is kept for
// `retain_s` after its end (the sensors' clock, so a restart does not reset it), and the
// oldest go first beyond `max_bytes`. With a state folder the maps stay on disk (the
// outbox's file, moved into `retained/`), else their tiles stay in memory.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/codec/temp_map_tiles.h"

namespace fleetmap::vehicle_agent {

struct RetainedMapsOptions {
  std::string folder;         // where files are kept (the outbox's state folder + "/retained")
  double retain_s = 86400.0;  // after a map's end, seconds
  int64_t max_bytes = int64_t{64} << 20;  // 0: keep nothing
};

struct RetainedMap {
  int32_t sequence = 0;
  int32_t version = 0;  // the map version its merge made (its MERGED acknowledgement)
  double end_s = 0.0;
  int64_t bytes = 0;
  std::vector<core::TempMapTile> tiles;  // without a folder
  std::string path;                      // with one: its file
};

class RetainedMaps {
 public:
  explicit RetainedMaps(RetainedMapsOptions options) : options_(std::move(options)) {}

  // The maps an earlier run kept (files named by Keep). Returns how many.
  int Load();
  // A merged map: `file` (with a folder: moved in; its size counts) or `tiles` (without).
  void Keep(int32_t sequence, int32_t version, std::vector<core::TempMapTile> tiles,
            const std::string& file);
  // Drops the maps that ended more than retain_s before `latest_end_s`.
  void DropEndedBefore(double latest_end_s);
  // Removes and returns the maps merged into versions after `version`, oldest first.
  std::vector<RetainedMap> TakeMergedAfter(int64_t version);

  size_t size() const { return maps_.size(); }
  int64_t bytes() const { return bytes_; }

 private:
  std::string PathOf(int32_t sequence, int32_t version, double end_s) const;
  void Drop(std::map<int32_t, RetainedMap>::iterator it);
  void FitBytes();

  RetainedMapsOptions options_;
  std::map<int32_t, RetainedMap> maps_;  // by sequence: oldest first
  int64_t bytes_ = 0;
};

}  // namespace fleetmap::vehicle_agent
