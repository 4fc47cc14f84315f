#include "vehicle_agent/node/lcm_links.h"

#include <poll.h>

#include <cerrno>
#include <cstring>

namespace fleetmap::vehicle_agent::node {

void LcmLinks::Route::OnMessage(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
  node->OnMessage(link, channel, rbuf->data, static_cast<int>(rbuf->data_size), (*clock)());
}

core::Result<std::unique_ptr<LcmLinks>> LcmLinks::Open(const LinkUrls& urls) {
  std::unique_ptr<LcmLinks> links(new LcmLinks());
  const std::string* by_link[3] = {&urls.sensor, &urls.uplink, &urls.downlink};
  std::vector<std::string> opened;
  for (int i = 0; i < 3; ++i) {
    const std::string& url = *by_link[i];
    size_t k = 0;
    while (k < opened.size() && opened[k] != url) ++k;
    if (k == opened.size()) {
      auto lcm = std::make_unique<lcm::LCM>(url);
      if (!lcm->good()) {
        const bool multicast = url.rfind("udpm://", 0) == 0 || url.empty();
        return core::IoError(
            std::string("cannot open the ") + LinkName(static_cast<Link>(i)) + " link '" + url +
            "'" +
            (multicast ? ": LCM needs a multicast route (on one host: run "
                         "scripts/setup_multicast.sh as root, or ip route add 224.0.0.0/4 dev lo)"
                       : ""));
      }
      links->instances_.push_back(std::move(lcm));
      opened.push_back(url);
    }
    links->index_[i] = static_cast<int>(k);
  }
  return links;
}

LcmLinks::~LcmLinks() { instances_.clear(); }

void LcmLinks::Subscribe(AgentNode* node, const std::function<double()>& clock) {
  clock_ = clock;
  for (const Subscription& s : node->Subscriptions()) {
    routes_.push_back(std::make_unique<Route>(Route{node, s.link, &clock_}));
    // Channel names are exact: vehicle ids hold no pattern characters (CheckVehicleId).
    lcm::Subscription* sub =
        Instance(s.link).subscribe(s.channel, &Route::OnMessage, routes_.back().get());
    // LCM keeps 30 messages per subscription by default and drops the rest silently; a scan
    // burst while a map swap runs must reach our own queue, which skips and counts
    // (input_queue.h). Odometry above all should not be lost: the tracker takes a gap as
    // motion only up to max_odometry_speed_mps and 5 s (input_guard.h). 2000: 10 s of
    // 200 Hz odometry (a simulator at 4x), at most ~7 MB of queued scans.
    if (sub != nullptr) sub->setQueueCapacity(2000);
  }
}

bool LcmLinks::Publish(Link link, const std::string& channel, const std::vector<uint8_t>& bytes) {
  return Instance(link).publish(channel, bytes.data(), static_cast<unsigned int>(bytes.size())) ==
         0;
}

core::Result<int> LcmLinks::Handle(double timeout_s, int max_messages) {
  std::vector<pollfd> fds;
  for (const auto& lcm : instances_) fds.push_back({lcm->getFileno(), POLLIN, 0});
  const int wait_ms = timeout_s <= 0.0 ? 0 : static_cast<int>(timeout_s * 1000.0 + 0.999);
  const int ready = poll(fds.data(), fds.size(), wait_ms);
  if (ready < 0) {
    if (errno == EINTR) return 0;  // a signal: the loop looks at its stop flag
    return core::IoError(std::string("poll on the LCM links failed: ") + std::strerror(errno));
  }
  int handled = 0;
  for (size_t i = 0; i < fds.size(); ++i) {
    if ((fds[i].revents & (POLLIN | POLLERR | POLLHUP)) == 0) continue;
    while (handled < max_messages) {
      const int r = instances_[i]->handleTimeout(0);
      if (r < 0) return core::IoError("LCM failed while receiving");
      if (r == 0) break;
      ++handled;
    }
  }
  return handled;
}

}  // namespace fleetmap::vehicle_agent::node
