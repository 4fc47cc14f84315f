// The LCM side of a node's links (docs/channels.md), the only place the processes open LCM:
// one LCM instance per link, or per distinct URL when asked to share, raw subscriptions (the
// node decodes: LCM's typed subscribe throws out of the handler on malformed data), and one
// wait over every link something subscribed to. A link nothing subscribes to opens no receive
// socket, so a process does not read back what it sends there.
#pragma once

#include <cstdint>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/result.h"
#include "edge/link.h"

namespace fleetmap::edge {

class LcmGroups {
 public:
  // A received message; `data` is valid during the call only.
  using Handler =
      std::function<void(Link link, const std::string& channel, const uint8_t* data, int size)>;

  // Opens a link for every entry of `urls`. With `share_same_url`, links given the same URL
  // share one instance (one socket; with memq:// they then see each other's messages).
  // An error names the link and the URL and, for multicast, how to get a route.
  static core::Result<std::unique_ptr<LcmGroups>> Open(const std::map<Link, std::string>& urls,
                                                       bool share_same_url);
  ~LcmGroups();

  // Hands every message on `link` whose channel matches `channel` (an LCM regular expression,
  // matched whole) to `handler`. LCM keeps up to `queue_capacity` of them waiting and drops
  // the rest silently (its default, 30, loses bursts of tiles or scans). `link` must be open.
  void Subscribe(Link link, const std::string& channel, int queue_capacity, Handler handler);
  // Sends at once; false when LCM refused the message or `link` is not open.
  bool Publish(Link link, const std::string& channel, const std::vector<uint8_t>& bytes);

  // Waits up to `timeout_s` for a message on any subscribed link, then handles those queued
  // (at most `max_messages`). Returns how many were handled: 0 after the timeout or a signal;
  // an error when LCM failed.
  core::Result<int> Handle(double timeout_s, int max_messages);

 private:
  struct Route {
    void OnMessage(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
    Link link;
    Handler handler;
  };
  LcmGroups() = default;
  lcm::LCM* Instance(Link link);

  // Routes are declared before the instances: members die in reverse order, so the LCM
  // instances (and their subscriptions) go first.
  std::vector<std::unique_ptr<Route>> routes_;
  std::vector<std::unique_ptr<lcm::LCM>> instances_;
  std::vector<bool> receiving_;      // by instance: something subscribed
  std::map<Link, size_t> instance_;  // by open link
};

}  // namespace fleetmap::edge
