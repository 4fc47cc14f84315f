// The agent's three LCM links (sensor, uplink, downlink; docs/channels.md): opens them,
// routes the node's subscriptions to AgentNode::OnMessage and publishes for it. Links given
// the same URL share one LCM instance (one socket). The only file of the node that holds
// LCM sockets; the loop (agent_loop.h) waits on their file descriptors.
#pragma once

#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <string>
#include <vector>

#include "vehicle_agent/node/agent_node.h"

namespace fleetmap::vehicle_agent::node {

struct LinkUrls {
  std::string sensor, uplink, downlink;  // lcmtypes/convert.h has the defaults
};

class LcmLinks : public Publisher {
 public:
  // Opens every link; an error names the URL and, for multicast, what to run.
  static core::Result<std::unique_ptr<LcmLinks>> Open(const LinkUrls& urls);
  ~LcmLinks() override;

  // Delivers the node's subscriptions to it, stamped with `clock()`. The node outlives the
  // links, or the links are destroyed first.
  void Subscribe(AgentNode* node, const std::function<double()>& clock);
  bool Publish(Link link, const std::string& channel, const std::vector<uint8_t>& bytes) override;

  // Waits up to `timeout_s` for a message on any link, then handles every message queued
  // (at most `max_messages`). Returns how many were handled; an error when LCM failed.
  core::Result<int> Handle(double timeout_s, int max_messages = 1000);

 private:
  struct Route {
    void OnMessage(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
    AgentNode* node;
    Link link;
    const std::function<double()>* clock;
  };
  LcmLinks() = default;
  lcm::LCM& Instance(Link link) { return *instances_[index_[static_cast<int>(link)]]; }

  // Routes are declared before the instances: members die in reverse order, so the LCM
  // instances (and their subscriptions) go first.
  std::vector<std::unique_ptr<Route>> routes_;
  std::function<double()> clock_;
  std::vector<std::unique_ptr<lcm::LCM>> instances_;
  int index_[3] = {0, 0, 0};  // instance of each Link
};

}  // namespace fleetmap::vehicle_agent::node
