#include "aggregator/node/lcm_links.h"

#include <algorithm>
#include <chrono>

#include "lcmtypes/convert.h"

namespace fleetmap::aggregator::node {

double WallClockS() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

core::Result<std::unique_ptr<LcmLinks>> LcmLinks::Open(const std::string& uplink_url,
                                                       const std::string& downlink_url) {
  std::unique_ptr<LcmLinks> links(new LcmLinks(uplink_url, downlink_url));
  for (const auto& [lcm, url] :
       {std::pair{&links->uplink_, uplink_url}, std::pair{&links->downlink_, downlink_url}}) {
    if (!lcm->good()) {
      return core::IoError("cannot open LCM at " + url +
                           " (no multicast route? on one host run scripts/setup_multicast.sh "
                           "as root; across hosts check the interface and ttl)");
    }
  }
  return links;
}

void LcmLinks::Bind(AggregatorNode* node) {
  node_ = node;
  // LCM queues at most 30 messages per subscription by default and silently drops the rest:
  // one temporary map is a burst of up to ~100 tiles, and a merge keeps us busy for a while.
  constexpr int kQueueCapacity = 4096;
  for (const char* channel :
       {lcmtypes::kTempMapChannelRegex, lcmtypes::kMapRequestChannel,
        lcmtypes::kCandidatesFreeChannelRegex, lcmtypes::kCandidatesHeldChannelRegex}) {
    lcm::Subscription* sub = uplink_.subscribe(channel, &LcmLinks::OnUplink, this);
    if (sub != nullptr) sub->setQueueCapacity(kQueueCapacity);
  }
}

void LcmLinks::OnUplink(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
  if (!node_ || rbuf->data_size > static_cast<uint32_t>(INT32_MAX)) return;
  node_->OnMessage(channel, rbuf->data, static_cast<int>(rbuf->data_size), WallClockS());
}

int LcmLinks::Poll(int timeout_ms) {
  if (Flush() > 0) timeout_ms = std::min(timeout_ms, 5);  // come back soon to send the rest
  return uplink_.handleTimeout(timeout_ms);
}

size_t LcmLinks::Flush() {
  int allowed = pacer_.Allowed(WallClockS());
  int sent = 0;
  for (; allowed > 0 && !queue_.empty(); --allowed, ++sent) {
    const Outgoing& m = queue_.front();
    lcm::LCM& lcm = m.link == Link::kUplink ? uplink_ : downlink_;
    lcm.publish(m.channel, m.bytes.data(), static_cast<unsigned int>(m.bytes.size()));
    queue_.pop_front();
  }
  pacer_.Sent(sent);
  return queue_.size();
}

bool LcmLinks::Publish(Link link, const std::string& channel, const std::vector<uint8_t>& bytes) {
  constexpr size_t kMaxQueued = 20000;  // ~ a hundred keyframes of a large site
  if (queue_.size() >= kMaxQueued) return false;
  queue_.push_back({link, channel, bytes});
  Flush();
  return true;
}

}  // namespace fleetmap::aggregator::node
