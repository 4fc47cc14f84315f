// The `inputs` section of the agent's configuration: where scans, odometry and external poses
// come from, and the settings of the SICK scanner and the CAN bus when they are the source.
#pragma once

#include "core/io/yaml_reader.h"
#include "vehicle_agent/node/agent_config.h"

namespace fleetmap::vehicle_agent::node {

// `n` is the section, undefined when the file has none (the defaults stay). A CAN mapping
// file is resolved against the configuration's folder.
core::Status ReadInputs(const core::YamlReader& r, const YAML::Node& n, AgentConfig& c);

}  // namespace fleetmap::vehicle_agent::node
