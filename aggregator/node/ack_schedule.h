// When the aggregator acknowledges a temporary map that is still incomplete, so that the
// vehicle's outbox resends only the tiles that are missing without an ack per tile. A PENDING
// acknowledgement goes out
//   - interval_s after a map's first tile if it is still incomplete then (its other tiles
//     usually arrive in the same burst, and the vehicle waits 1 s before it resends), then at
//     most every interval_s while new tiles come in;
//   - at once when a tile arrives that the aggregator already has (the vehicle did not get
//     the last acknowledgement), unless one went out within interval_s.
// Resent tiles of a map already merged or rejected get one answer per interval_s. Time is
// passed in.
#pragma once

#include <map>
#include <vector>

#include "aggregator/node/map_key.h"

namespace fleetmap::aggregator::node {

class AckSchedule {
 public:
  explicit AckSchedule(double interval_s) : interval_s_(interval_s) {}

  // A tile of an incomplete map arrived; true when a PENDING acknowledgement is due now.
  bool OnTile(const MapKey& key, bool repeated, double now_s);
  // A map restored after a restart: known, nothing to acknowledge yet.
  void Restore(const MapKey& key, double now_s);
  // Incomplete maps whose PENDING acknowledgement is due.
  std::vector<MapKey> Due(double now_s);
  void Acked(const MapKey& key, double now_s);
  // Incomplete maps that received no tile for timeout_s.
  std::vector<MapKey> Stale(double now_s, double timeout_s) const;
  // The map is complete or dropped.
  void Forget(const MapKey& key) { incomplete_.erase(key); }

  // A tile of a map already handled arrived; true when it is to be answered now.
  bool FinalAckDue(const MapKey& key, double now_s);

  size_t incomplete() const { return incomplete_.size(); }

 private:
  struct Entry {
    double first_s = 0.0;      // first tile
    double last_tile_s = 0.0;  // latest tile
    double last_ack_s = 0.0;   // latest PENDING ack (valid if acked)
    bool acked = false;
    bool dirty = false;  // tiles arrived since the latest ack
  };
  double interval_s_;
  std::map<MapKey, Entry> incomplete_;
  std::map<MapKey, double> final_acks_;  // handled map -> latest answer, pruned by Due
};

}  // namespace fleetmap::aggregator::node
