#include "edge/lcm_groups.h"

#include <poll.h>

#include <cerrno>
#include <climits>
#include <cstring>

namespace fleetmap::edge {

void LcmGroups::Route::OnMessage(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
  if (rbuf->data_size > static_cast<uint32_t>(INT_MAX)) return;
  handler(link, channel, static_cast<const uint8_t*>(rbuf->data),
          static_cast<int>(rbuf->data_size));
}

core::Result<std::unique_ptr<LcmGroups>> LcmGroups::Open(const std::map<Link, std::string>& urls,
                                                         bool share_same_url) {
  std::unique_ptr<LcmGroups> groups(new LcmGroups());
  std::map<std::string, size_t> by_url;
  for (const auto& [link, url] : urls) {
    if (share_same_url && by_url.count(url)) {
      groups->instance_[link] = by_url[url];
      continue;
    }
    auto lcm = std::make_unique<lcm::LCM>(url);
    if (!lcm->good()) {
      const bool multicast = url.rfind("udpm://", 0) == 0 || url.empty();
      return core::IoError(
          std::string("cannot open the ") + LinkName(link) + " link '" + url + "'" +
          (multicast ? ": LCM needs a multicast route (on one host: run "
                       "scripts/setup_multicast.sh as root, or ip route add 224.0.0.0/4 dev lo; "
                       "across hosts check the interface and ttl)"
                     : ""));
    }
    by_url[url] = groups->instances_.size();
    groups->instance_[link] = groups->instances_.size();
    groups->instances_.push_back(std::move(lcm));
    groups->receiving_.push_back(false);
  }
  return groups;
}

LcmGroups::~LcmGroups() { instances_.clear(); }

lcm::LCM* LcmGroups::Instance(Link link) {
  const auto it = instance_.find(link);
  return it == instance_.end() ? nullptr : instances_[it->second].get();
}

void LcmGroups::Subscribe(Link link, const std::string& channel, int queue_capacity,
                          Handler handler) {
  lcm::LCM* lcm = Instance(link);
  if (lcm == nullptr) return;
  routes_.push_back(std::make_unique<Route>(Route{link, std::move(handler)}));
  lcm::Subscription* sub = lcm->subscribe(channel, &Route::OnMessage, routes_.back().get());
  if (sub != nullptr) sub->setQueueCapacity(queue_capacity);
  receiving_[instance_.at(link)] = true;
}

bool LcmGroups::Publish(Link link, const std::string& channel, const std::vector<uint8_t>& bytes) {
  lcm::LCM* lcm = Instance(link);
  return lcm != nullptr &&
         lcm->publish(channel, bytes.data(), static_cast<unsigned int>(bytes.size())) == 0;
}

core::Result<int> LcmGroups::Handle(double timeout_s, int max_messages) {
  std::vector<pollfd> fds;
  std::vector<lcm::LCM*> polled;
  for (size_t i = 0; i < instances_.size(); ++i) {
    if (!receiving_[i]) continue;  // getFileno() would open a receive socket
    fds.push_back({instances_[i]->getFileno(), POLLIN, 0});
    polled.push_back(instances_[i].get());
  }
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
      const int r = polled[i]->handleTimeout(0);
      if (r < 0) return core::IoError("LCM failed while receiving");
      if (r == 0) break;
      ++handled;
    }
  }
  return handled;
}

}  // namespace fleetmap::edge
