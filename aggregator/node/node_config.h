// The configuration of the fleetmap-aggregator process: its YAML file (every key optional,
// unknown keys refused) on top of the defaults in the options structs; command-line flags
// override it afterwards. docs/aggregator_process.md lists every key with its default and
// unit, in the order of the structs.
#pragma once

#include <string>

#include "aggregator/aggregator.h"
#include "aggregator/node/node_options.h"

namespace fleetmap::aggregator::node {

struct AggregatorProcessConfig {
  std::string uplink_url;    // where vehicles send; default lcmtypes::kDefaultUplinkUrl
  std::string downlink_url;  // where the aggregator answers; lcmtypes::kDefaultDownlinkUrl
  std::string state_dir;     // persistence folder; empty: memory only
  // The fleet key file (docs/security.md), read into node.fleet_key by the process; empty:
  // unauthenticated.
  std::string key_file;
  AggregatorNodeOptions node;
  AggregatorOptions aggregator;
  core::Status Validate() const;
};

AggregatorProcessConfig DefaultProcessConfig();

// `name` prefixes every error ("agg.yaml:7: node.status_period_s: must be > 0").
core::Result<AggregatorProcessConfig> ParseProcessConfig(const std::string& yaml_text,
                                                         const std::string& name);
core::Result<AggregatorProcessConfig> LoadProcessConfig(const std::string& path);

}  // namespace fleetmap::aggregator::node
