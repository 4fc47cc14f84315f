#include "aggregator/node/node_io.h"

namespace fleetmap::aggregator::node {

const char* LinkName(Link link) { return link == Link::kUplink ? "uplink" : "downlink"; }

}  // namespace fleetmap::aggregator::node
