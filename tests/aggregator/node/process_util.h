// Running fleetmap-aggregator from a test (tests/support/process.h): its binary and its final
// line.
#pragma once

#include <sstream>
#include <string>

#include "tests/support/process.h"

namespace fleetmap::aggregator::node::testing {

inline std::string AggregatorBinary() { return FLEETMAP_AGGREGATOR_BIN; }

using fleetmap::testing::Process;
using fleetmap::testing::ReadText;

// The last line of `text` starting with "aggregator: version", or "".
inline std::string FinalLineOf(const std::string& text) {
  std::istringstream in(text);
  std::string line, last;
  while (std::getline(in, line))
    if (line.rfind("aggregator: version", 0) == 0) last = line;
  return last;
}

}  // namespace fleetmap::aggregator::node::testing
