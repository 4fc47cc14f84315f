#include "aggregator/node/lcm_links.h"

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
  uplink_.subscribe(lcmtypes::kTempMapChannelRegex, &LcmLinks::OnUplink, this);
  uplink_.subscribe(lcmtypes::kMapRequestChannel, &LcmLinks::OnUplink, this);
}

void LcmLinks::OnUplink(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
  if (!node_ || rbuf->data_size > static_cast<uint32_t>(INT32_MAX)) return;
  node_->OnMessage(channel, rbuf->data, static_cast<int>(rbuf->data_size), WallClockS());
}

int LcmLinks::Poll(int timeout_ms) { return uplink_.handleTimeout(timeout_ms); }

bool LcmLinks::Publish(Link link, const std::string& channel, const std::vector<uint8_t>& bytes) {
  lcm::LCM& lcm = link == Link::kUplink ? uplink_ : downlink_;
  return lcm.publish(channel, bytes.data(), static_cast<unsigned int>(bytes.size())) == 0;
}

}  // namespace fleetmap::aggregator::node
