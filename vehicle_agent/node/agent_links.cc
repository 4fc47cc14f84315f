#include "vehicle_agent/node/agent_links.h"

namespace fleetmap::vehicle_agent::node {

core::Result<std::unique_ptr<AgentLinks>> AgentLinks::Open(const LinkUrls& urls) {
  auto groups = edge::LcmGroups::Open({{Link::kSensor, urls.sensor},
                                       {Link::kUplink, urls.uplink},
                                       {Link::kDownlink, urls.downlink}},
                                      /*share_same_url=*/true);
  if (!groups.ok()) return groups.status();
  return std::unique_ptr<AgentLinks>(new AgentLinks(std::move(groups).value()));
}

void AgentLinks::Subscribe(AgentNode* node, const std::function<double()>& clock) {
  // LCM keeps 30 messages per subscription by default and drops the rest silently; a scan
  // burst while a map swap runs must reach our own queue, which skips and counts
  // (input_queue.h). Odometry above all should not be lost: the tracker takes a gap as
  // motion only up to max_odometry_speed_mps and 5 s (input_guard.h). 2000: 10 s of
  // 200 Hz odometry (a simulator at 4x), at most ~7 MB of queued scans.
  constexpr int kQueueCapacity = 2000;
  for (const Subscription& s : node->Subscriptions()) {
    // Channel names are exact: vehicle ids hold no pattern characters (CheckVehicleId).
    groups_->Subscribe(
        s.link, s.channel, kQueueCapacity,
        [node, clock](Link link, const std::string& channel, const uint8_t* data, int size) {
          node->OnMessage(link, channel, data, size, clock());
        });
  }
}

bool AgentLinks::Publish(Link link, const std::string& channel, const std::vector<uint8_t>& bytes) {
  return groups_->Publish(link, channel, bytes);
}

core::Result<int> AgentLinks::Handle(double timeout_s, int max_messages) {
  return groups_->Handle(timeout_s, max_messages);
}

}  // namespace fleetmap::vehicle_agent::node
