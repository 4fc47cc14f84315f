// The aggregator's two LCM links on edge::LcmGroups: it receives on the uplink (TEMPMAP_.*,
// MAP_REQUEST, CANDIDATES_*) and sends on the downlink, paced within a budget of bytes and
// messages per second (docs/channels.md, "The downlink's budget"). What is published waits in
// one queue, in order; traffic that can wait (keyframe tiles) asks RoomBytes() first and is
// published only when nothing waits, so acknowledgements and deltas never wait behind it.
// Nothing subscribes on the downlink, so LCM opens no receive socket there and our own
// messages are not read back.
#pragma once

#include <deque>
#include <memory>
#include <string>

#include "aggregator/node/aggregator_node.h"
#include "core/codec/send_pacer.h"
#include "edge/lcm_groups.h"

namespace fleetmap::aggregator::node {

class AggregatorLinks : public Publisher {
 public:
  // Opens both links. The error names the URL and says how to get a multicast route.
  static core::Result<std::unique_ptr<AggregatorLinks>> Open(const std::string& uplink_url,
                                                             const std::string& downlink_url,
                                                             const core::PacerOptions& downlink);

  // Subscribes `node` (which outlives these links) to the uplink channels; every message
  // is handed over with the wall clock as its receive time.
  void Bind(AggregatorNode* node);
  // Sends what the pacer allows of the queued messages, then handles what arrives within
  // timeout_ms (shorter while messages wait): > 0 handled, 0 timed out, < 0 error.
  int Poll(int timeout_ms);
  // Sends what the pacer allows now; returns how many messages still wait.
  size_t Flush();
  // Queues a message; it goes out paced (core/codec/send_pacer.h: a burst of tiles would
  // overflow slow readers such as lcm-logger, and a shared channel). False when the queue
  // holds more than kMaxQueuedS of the byte budget (the message is dropped).
  bool Publish(Link link, const std::string& channel, const std::vector<uint8_t>& bytes) override;
  // The bytes the budget allows now when nothing waits in the queue; 0 otherwise.
  size_t RoomBytes(Link link) const override;

  // Seconds of the byte budget the queue holds at most.
  static constexpr double kMaxQueuedS = 10.0;

 private:
  AggregatorLinks(std::unique_ptr<edge::LcmGroups> groups, const core::PacerOptions& downlink)
      : groups_(std::move(groups)),
        // Without a byte budget, as many as a hundred keyframes of a large site.
        max_queued_bytes_(downlink.bytes_per_s > 0.0 ? downlink.bytes_per_s * kMaxQueuedS : 64e6),
        pacer_(downlink) {}

  struct Outgoing {
    Link link;
    std::string channel;
    std::vector<uint8_t> bytes;
  };
  std::unique_ptr<edge::LcmGroups> groups_;
  const double max_queued_bytes_;
  std::deque<Outgoing> queue_;
  size_t queued_bytes_ = 0;
  core::SendPacer pacer_;
};

// Seconds since the Unix epoch, the time base of every utime on the wire.
double WallClockS();

}  // namespace fleetmap::aggregator::node
