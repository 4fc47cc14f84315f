// The aggregator's two LCM links on edge::LcmGroups: it receives on the uplink (TEMPMAP_.*,
// MAP_REQUEST, CANDIDATES_*) and sends on the downlink, paced. Nothing subscribes on the
// downlink, so LCM opens no receive socket there and our own messages are not read back.
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
                                                             const std::string& downlink_url);

  // Subscribes `node` (which outlives these links) to the uplink channels; every message
  // is handed over with the wall clock as its receive time.
  void Bind(AggregatorNode* node);
  // Sends what the pacer allows of the queued messages, then handles what arrives within
  // timeout_ms (shorter while messages wait): > 0 handled, 0 timed out, < 0 error.
  int Poll(int timeout_ms);
  // Sends what the pacer allows now; returns how many messages still wait.
  size_t Flush();
  // Queues a message; it goes out paced (core/codec/send_pacer.h: a keyframe is a burst of ~100
  // tiles, which slow readers such as lcm-logger would otherwise lose). False when the queue
  // is full (the message is dropped).
  bool Publish(Link link, const std::string& channel, const std::vector<uint8_t>& bytes) override;

 private:
  explicit AggregatorLinks(std::unique_ptr<edge::LcmGroups> groups) : groups_(std::move(groups)) {}

  struct Outgoing {
    Link link;
    std::string channel;
    std::vector<uint8_t> bytes;
  };
  std::unique_ptr<edge::LcmGroups> groups_;
  std::deque<Outgoing> queue_;
  core::SendPacer pacer_;
};

// Seconds since the Unix epoch, the time base of every utime on the wire.
double WallClockS();

}  // namespace fleetmap::aggregator::node
