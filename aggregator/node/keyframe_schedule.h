// Which tiles of the current map go out next as MAP_KEYFRAME. Two sources, asked tiles first:
//   - tiles vehicles asked for (MAP_REQUEST): each waits once however many vehicles or
//     requests asked for it, so one answer serves everyone who asked (a fleet restarting at
//     once costs one keyframe, a vehicle asking twice costs nothing more);
//   - a rolling keyframe: every tile in turn, one whole round per period_s, so that a vehicle
//     that missed everything converges without a burst, however large the map.
// Only tile indices wait here: the caller cuts each tile from the current map as it sends it
// (core::MapReplica assembles tiles of several versions), so none goes out stale and nothing
// grows with the requests. Time is passed in.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

namespace fleetmap::aggregator::node {

class KeyframeSchedule {
 public:
  // `num_tiles` of the current map; one rolling round per `period_s` (0: no rolling keyframe),
  // paced from `now_s`.
  KeyframeSchedule(int32_t num_tiles, double period_s, double now_s);

  // Tiles by linear index (any out of range ignored); empty: every tile.
  void Ask(const std::vector<int32_t>& tiles);
  // An asked tile to send now (in index order from the last sent, round robin), or nothing.
  // The caller sends these first. Each tile returned counts as sent.
  std::optional<int32_t> NextAsked();
  // The next tile of the rolling keyframe when the round's pace allows one at now_s, or
  // nothing. Each tile returned counts as sent.
  std::optional<int32_t> NextRolling(double now_s);

  int32_t asked() const { return asked_count_; }  // asked tiles not yet sent
  int64_t rounds() const { return rounds_; }      // rolling rounds completed
  int64_t asked_sent() const { return asked_sent_; }

 private:
  double CreditAt(double now_s) const;

  int32_t num_tiles_;
  double tiles_per_s_;   // the rolling pace; 0: none
  double credit_ = 0.0;  // rolling tiles that may go at last_s_
  double last_s_;
  std::vector<bool> asked_;
  int32_t asked_count_ = 0;
  int32_t asked_cursor_ = 0;
  int32_t rolling_cursor_ = 0;
  int64_t rounds_ = 0;
  int64_t asked_sent_ = 0;
};

}  // namespace fleetmap::aggregator::node
