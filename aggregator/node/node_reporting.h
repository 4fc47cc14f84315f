// Where every part of the aggregator node reports: the node's one set of counters (what
// STATUS publishes) and its one log. Shared rather than kept per part, so that STATUS adds up
// to the node as a whole and a cause of bad input is logged once, whichever part met it.
#pragma once

#include <cstdint>
#include <string>

#include "aggregator/node/node_counters.h"
#include "aggregator/node/node_io.h"

namespace fleetmap::aggregator::node {

struct NodeReporting {
  NodeCounters& counters;
  CauseLog& log;

  // Bad input changes nothing but its cause's `counter` (a field of `counters`) and, the
  // first time the cause is seen, the log: a stream of broken messages cannot flood it.
  void Refuse(const std::string& cause, int64_t& counter, const std::string& line) const {
    ++counter;
    log.Once(cause, line);
  }
};

}  // namespace fleetmap::aggregator::node
