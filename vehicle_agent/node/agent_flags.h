// The command line of fleetmap-agent: --config FILE.yaml first, then flags that override
// single keys of it (the ones a launcher passes per vehicle). Nothing here exits or prints:
// the main does that with what this returns.
#pragma once

#include <string>
#include <vector>

#include "vehicle_agent/node/agent_config.h"

namespace fleetmap::vehicle_agent::node {

struct AgentCommandLine {
  bool help = false;
  bool version = false;
  AgentConfig config;  // the file (if any) with the flags applied, FinishDefaults done
};

// Parses argv (argv[0] is skipped). Errors name the flag: unknown flags, missing or bad
// values, a config file that does not load, a configuration that does not validate.
core::Result<AgentCommandLine> ParseAgentCommandLine(const std::vector<std::string>& args);

// "X,Y,THETA": three finite numbers (metres, metres, radians).
core::Result<core::Pose2> ParsePoseFlag(const std::string& text, const std::string& flag);

// The --help text.
std::string AgentUsage();

}  // namespace fleetmap::vehicle_agent::node
