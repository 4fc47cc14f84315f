#include "vehicle_agent/node/node_io.h"

namespace fleetmap::vehicle_agent::node {

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

}  // namespace fleetmap::vehicle_agent::node
