#include "aggregator/node/aggregator_links.h"

#include <algorithm>
#include <chrono>

#include "lcmtypes/convert.h"

namespace fleetmap::aggregator::node {

double WallClockS() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

core::Result<std::unique_ptr<AggregatorLinks>> AggregatorLinks::Open(
    const std::string& uplink_url, const std::string& downlink_url) {
  // Never one instance for both, even on one URL: the uplink's TEMPMAP_.* would match our own
  // TEMPMAP_ACK.
  auto groups =
      edge::LcmGroups::Open({{Link::kUplink, uplink_url}, {Link::kDownlink, downlink_url}},
                            /*share_same_url=*/false);
  if (!groups.ok()) return groups.status();
  return std::unique_ptr<AggregatorLinks>(new AggregatorLinks(std::move(groups).value()));
}

void AggregatorLinks::Bind(AggregatorNode* node) {
  // LCM queues at most 30 messages per subscription by default and silently drops the rest:
  // one temporary map is a burst of up to ~100 tiles, and a merge keeps us busy for a while.
  constexpr int kQueueCapacity = 4096;
  for (const char* channel :
       {lcmtypes::kTempMapChannelRegex, lcmtypes::kMapRequestChannel,
        lcmtypes::kCandidatesFreeChannelRegex, lcmtypes::kCandidatesHeldChannelRegex}) {
    groups_->Subscribe(Link::kUplink, channel, kQueueCapacity,
                       [node](Link, const std::string& channel, const uint8_t* data, int size) {
                         node->OnMessage(channel, data, size, WallClockS());
                       });
  }
}

int AggregatorLinks::Poll(int timeout_ms) {
  if (Flush() > 0) timeout_ms = std::min(timeout_ms, 5);  // come back soon to send the rest
  const core::Result<int> handled = groups_->Handle(timeout_ms / 1000.0, /*max_messages=*/1);
  return handled.ok() ? *handled : -1;
}

size_t AggregatorLinks::Flush() {
  int allowed = pacer_.Allowed(WallClockS());
  int sent = 0;
  for (; allowed > 0 && !queue_.empty(); --allowed, ++sent) {
    const Outgoing& m = queue_.front();
    groups_->Publish(m.link, m.channel, m.bytes);
    queue_.pop_front();
  }
  pacer_.Sent(sent);
  return queue_.size();
}

bool AggregatorLinks::Publish(Link link, const std::string& channel,
                              const std::vector<uint8_t>& bytes) {
  constexpr size_t kMaxQueued = 20000;  // ~ a hundred keyframes of a large site
  if (queue_.size() >= kMaxQueued) return false;
  queue_.push_back({link, channel, bytes});
  Flush();
  return true;
}

}  // namespace fleetmap::aggregator::node
