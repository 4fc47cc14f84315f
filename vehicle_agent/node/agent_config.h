// The whole configuration of fleetmap-agent: the node's options, its inputs (LCM, a SICK
// scanner, CAN odometry), the links' URLs and the process's own settings. Read from a YAML
// file whose every key, default and unit docs/agent_process.md lists; unknown keys are
// errors (a misspelt key must not silently keep its default). Command-line flags
// (agent_flags.h) override the file.
#pragma once

#include <string>

#include "vehicle_agent/node/agent_links.h"
#include "vehicle_agent/node/agent_node_options.h"
#include "vehicle_agent/node/can_odometry_input.h"
#include "vehicle_agent/node/sick_scan_input.h"

namespace fleetmap::vehicle_agent::node {

enum class ScanSource { kLcm, kSick };
enum class OdomSource { kLcm, kCan, kNone };

struct AgentConfig {
  AgentNodeOptions node;
  std::string map_yaml;        // static map (map_server YAML) held as version 0; empty: none
  std::string final_map_yaml;  // where the current map is written at exit; empty: not written
  std::string key_file;        // the fleet key (docs/security.md); empty: unauthenticated
  LinkUrls urls;               // defaults: lcmtypes/convert.h
  ScanSource scan_source = ScanSource::kLcm;
  OdomSource odom_source = OdomSource::kLcm;
  SickInputOptions sick;
  CanInputOptions can;
  double loop_wait_s = 0.05;      // longest wait of the loop for input, s, (0, 0.1]
  double shutdown_drain_s = 2.0;  // LoopOptions::shutdown_drain_s, s, [0, 60]
  double duration_s = 0.0;        // stop after this long, s; 0: until SIGINT/SIGTERM
  bool quiet = false;             // only warnings, errors and the final line
  // Whether the file or a flag said where the first pose comes from. If not: the first
  // external pose when inputs.external_pose is on, else global localization.
  bool initial_pose_explicit = false;

  AgentConfig();
  // Settles what depends on several keys and flags (the initial pose's source, which inputs
  // come over LCM); call once the file and the flags are in, before Validate.
  void FinishDefaults();
  // Consistency of the whole, naming the bad key.
  core::Status Validate() const;
};

// Parses YAML text; `path` names errors and resolves relative file names (map, state_dir,
// final_map, inputs.can.mapping_file) against its folder.
core::Result<AgentConfig> ParseAgentConfig(const std::string& yaml_text, const std::string& path);
core::Result<AgentConfig> LoadAgentConfig(const std::string& path);

}  // namespace fleetmap::vehicle_agent::node
