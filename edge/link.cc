#include "edge/link.h"

namespace fleetmap::edge {

const char* LinkName(Link link) {
  switch (link) {
    case Link::kSensor:
      return "sensor";
    case Link::kUplink:
      return "uplink";
    case Link::kDownlink:
      return "downlink";
  }
  return "?";
}

}  // namespace fleetmap::edge
