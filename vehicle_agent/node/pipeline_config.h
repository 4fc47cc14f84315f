// The on-board pipeline's sections of the agent's configuration: `localization`,
// `divergence`, `builder` (the temporary maps) and `candidate_watch`. Each reader takes its
// section, undefined when the file has none (the defaults stay).
#pragma once

#include "core/io/yaml_reader.h"
#include "vehicle_agent/agent_pipeline.h"

namespace fleetmap::vehicle_agent::node {

core::Status ReadLocalization(const core::YamlReader& r, const YAML::Node& n, LocalizerOptions& l);
core::Status ReadDivergence(const core::YamlReader& r, const YAML::Node& n, DivergenceOptions& d);
core::Status ReadBuilder(const core::YamlReader& r, const YAML::Node& n, TempMapBuilderOptions& b);
// Also sets the pipeline's candidate_watch_max_sigma_m (key max_sigma_m).
core::Status ReadCandidateWatch(const core::YamlReader& r, const YAML::Node& n,
                                AgentPipelineOptions& p);

}  // namespace fleetmap::vehicle_agent::node
