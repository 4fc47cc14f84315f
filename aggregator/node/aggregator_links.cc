#include "aggregator/node/aggregator_links.h"

#include <algorithm>
#include <chrono>

#include "lcmtypes/convert.h"

namespace fleetmap::aggregator::node {

double WallClockS() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

core::Result<std::unique_ptr<AggregatorLinks>> AggregatorLinks::Open(
    const std::string& uplink_url, const std::string& downlink_url,
    const core::PacerOptions& downlink) {
  FLEETMAP_RETURN_IF_ERROR(downlink.Validate().WithContext("downlink"));
  // Never one instance for both, even on one URL: the uplink's TEMPMAP_.* would match our own
  // TEMPMAP_ACK.
  auto groups =
      edge::LcmGroups::Open({{Link::kUplink, uplink_url}, {Link::kDownlink, downlink_url}},
                            /*share_same_url=*/false);
  if (!groups.ok()) return groups.status();
  return std::unique_ptr<AggregatorLinks>(new AggregatorLinks(std::move(groups).value(), downlink));
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
  const double now_s = WallClockS();
  while (!queue_.empty() && pacer_.MaySend(now_s)) {
    const Outgoing& m = queue_.front();
    groups_->Publish(m.link, m.channel, m.bytes);
    pacer_.Sent(1, m.bytes.size());
    queued_bytes_ -= m.bytes.size();
    queue_.pop_front();
  }
  return queue_.size();
}

size_t AggregatorLinks::RoomBytes(Link) const {
  if (!queue_.empty()) return 0;
  return static_cast<size_t>(std::min(pacer_.BytesAllowed(WallClockS()), 1e15));
}

bool AggregatorLinks::Publish(Link link, const std::string& channel,
                              const std::vector<uint8_t>& bytes) {
  if (static_cast<double>(queued_bytes_ + bytes.size()) > max_queued_bytes_) return false;
  queue_.push_back({link, channel, bytes});
  queued_bytes_ += bytes.size();
  Flush();
  return true;
}

}  // namespace fleetmap::aggregator::node
