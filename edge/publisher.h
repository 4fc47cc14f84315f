// Where a node sends without owning a socket: the process binds it to LCM, tests to memory.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "edge/link.h"

namespace fleetmap::edge {

class Publisher {
 public:
  virtual ~Publisher() = default;
  // Sends one encoded message; returns false when the transport refused it (counted).
  virtual bool Publish(Link link, const std::string& channel,
                       const std::vector<uint8_t>& bytes) = 0;
  // Bytes `link` can send now without queueing them behind messages already waiting, within
  // its byte budget: traffic that can wait (keyframe tiles) is sent only while there is room,
  // so that it never delays what cannot. Unlimited where the transport has no budget.
  virtual size_t RoomBytes(Link /*link*/) const { return std::numeric_limits<size_t>::max(); }
};

}  // namespace fleetmap::edge
