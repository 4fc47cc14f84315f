// The vehicle's outbox for temporary maps: every closed map is kept (in memory and, with a
// state folder, on disk) until the aggregator acknowledges it, and its tiles that the
// aggregator has not confirmed are sent again with exponential backoff, back to the first
// interval whenever an acknowledgement confirms new tiles (a lossy link, not an absent
// aggregator). On restart the
// outbox reloads what it still had to send. Free of LCM: the agent process sends what Due()
// returns and passes acknowledgements to OnAck().
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/codec/temp_map_tiles.h"
#include "vehicle_agent/retained_maps.h"

namespace fleetmap::vehicle_agent {

struct OutboxOptions {
  std::string state_dir;        // where pending maps are kept on disk; empty: memory only
  double first_resend_s = 1.0;  // wait for an acknowledgement this long before resending
  double max_resend_s = 16.0;   // backoff doubles up to this while no new tile is confirmed
  int max_pending_maps = 64;    // the oldest is dropped (and counted) beyond this
  int tile_size_cells = 64;
  // Merged maps are kept this long after their end, to be sent again if the aggregator loses
  // them (retained_maps.h), up to this many bytes; 0 bytes: none are kept.
  double retain_merged_s = 86400.0;
  int64_t max_retained_bytes = int64_t{64} << 20;
  core::Status Validate() const;
};

enum class AckOutcome { kPending, kMerged, kRejected, kDuplicate };

struct OutboxCounters {
  int64_t maps_added = 0, maps_done = 0, maps_dropped = 0;
  int64_t tiles_sent = 0, tiles_resent = 0;
  int64_t persist_errors = 0;
  int64_t maps_resent_after_recovery = 0;  // merged maps sent again: the aggregator lost them
};

class TempMapOutbox {
 public:
  explicit TempMapOutbox(const OutboxOptions& options);

  // Reloads maps left in the state folder by an earlier run (corrupt files are counted,
  // moved aside and skipped). Returns how many were loaded.
  int LoadPersisted(double now_s);
  core::Status Add(const core::TempMap& map, double now_s);
  // Tiles to send now: all tiles of new maps, and the unconfirmed tiles of maps whose resend
  // time has come.
  std::vector<core::TempMapTile> Due(double now_s);
  // An acknowledgement: received tile indices, and whether the map is finished with. A map
  // merged (or a duplicate of one merged) into `map_version` is retained.
  void OnAck(int32_t sequence, const std::vector<int32_t>& received, AckOutcome outcome,
             int32_t map_version = -1);
  // The aggregator recovered its map at `version` and lost what came after: the retained
  // maps merged into later versions are pending again, sent now. Returns how many.
  int ResendMergedAfter(int64_t version, double now_s);

  size_t pending() const { return pending_.size(); }
  const RetainedMaps& retained() const { return retained_; }
  const OutboxCounters& counters() const { return counters_; }

 private:
  struct Entry {
    std::vector<core::TempMapTile> tiles;
    std::set<int32_t> confirmed;
    double next_send_s = 0.0;
    double last_send_s = 0.0;
    double backoff_s = 0.0;  // the wait after the next send
    bool sent_once = false;
  };
  std::string PathOf(int32_t sequence) const;
  void Insert(const core::TempMap& map, double now_s);
  void InsertTiles(int32_t sequence, std::vector<core::TempMapTile> tiles, double now_s);

  OutboxOptions options_;
  std::map<int32_t, Entry> pending_;  // by sequence: oldest first
  RetainedMaps retained_;
  OutboxCounters counters_;
};

}  // namespace fleetmap::vehicle_agent
