// MAP_REQUESTs waiting to be answered, coalesced: many vehicles asking at once (after a
// restart, or a lost delta everyone missed) cost one answer. Deltas are resent at the next
// flush, from the oldest version asked for; keyframes (a hundred tiles for a hall) go out at
// most once per min_interval_s, every tile asked for by anyone in one round. Time is passed
// in.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <set>
#include <vector>

namespace fleetmap::aggregator::node {

struct RequestPlan {
  std::optional<uint64_t> deltas_from;  // resend every version from here to the current
  bool full_keyframe = false;           // every tile of the current map
  std::vector<int32_t> keyframe_tiles;  // only these (when not full), ascending
  bool keyframe() const { return full_keyframe || !keyframe_tiles.empty(); }
};

class RequestQueue {
 public:
  explicit RequestQueue(double keyframe_min_interval_s)
      : keyframe_min_interval_s_(keyframe_min_interval_s) {}

  void AddDeltas(uint64_t from_version);
  // Keyframe tiles by linear index; empty: the whole map.
  void AddKeyframe(const std::vector<int32_t>& tiles);
  // What to send now; a keyframe waits while one went out less than min_interval_s ago.
  // The caller sends what it returns.
  RequestPlan Take(double now_s);
  // A whole keyframe went out unasked (the periodic one): it answers every waiting request.
  void WholeKeyframeSent(double now_s);
  bool keyframe_waiting() const { return full_ || !tiles_.empty(); }

 private:
  double keyframe_min_interval_s_;
  std::optional<uint64_t> deltas_from_;
  bool full_ = false;
  std::set<int32_t> tiles_;
  double last_keyframe_s_ = -std::numeric_limits<double>::infinity();
};

}  // namespace fleetmap::aggregator::node
