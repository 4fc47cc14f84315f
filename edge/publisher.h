// Where a node sends without owning a socket: the process binds it to LCM, tests to memory.
#pragma once

#include <cstdint>
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
};

}  // namespace fleetmap::edge
