// The agent's three LCM links (sensor, uplink, downlink; docs/channels.md) on
// edge::LcmGroups: routes the node's subscriptions to AgentNode::OnMessage and publishes for
// it. Links given the same URL share one LCM instance (one socket). The loop (agent_loop.h)
// waits in Handle().
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "edge/lcm_groups.h"
#include "vehicle_agent/node/agent_node.h"

namespace fleetmap::vehicle_agent::node {

struct LinkUrls {
  std::string sensor, uplink, downlink;  // lcmtypes/convert.h has the defaults
};

class AgentLinks : public Publisher {
 public:
  // Opens every link; an error names the URL and, for multicast, what to run.
  static core::Result<std::unique_ptr<AgentLinks>> Open(const LinkUrls& urls);

  // Delivers the node's subscriptions to it, stamped with `clock()`. The node outlives the
  // links, or the links are destroyed first.
  void Subscribe(AgentNode* node, const std::function<double()>& clock);
  bool Publish(Link link, const std::string& channel, const std::vector<uint8_t>& bytes) override;

  // Waits up to `timeout_s` for a message on any link, then handles every message queued
  // (at most `max_messages`). Returns how many were handled; an error when LCM failed.
  core::Result<int> Handle(double timeout_s, int max_messages = 1000);

 private:
  explicit AgentLinks(std::unique_ptr<edge::LcmGroups> groups) : groups_(std::move(groups)) {}
  std::unique_ptr<edge::LcmGroups> groups_;
};

}  // namespace fleetmap::vehicle_agent::node
