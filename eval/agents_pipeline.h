// The real system, in-process: every simulated vehicle runs the on-board AgentPipeline on the
// current map (localization, divergence, temporary maps), every closed temporary map goes to
// the aggregator (alignment and merge), and every accepted merge's new map version is given
// to every vehicle, as MAP_DELTA would. What fleetmap-agent and fleetmap-aggregator do over
// LCM, minus the network, so the evaluation scores the method itself.
#pragma once

#include <memory>

#include "aggregator/aggregator.h"
#include "eval/pipeline.h"
#include "vehicle_agent/agent_pipeline.h"

namespace fleetmap::eval {

struct AgentsPipelineOptions {
  vehicle_agent::AgentPipelineOptions agent;  // vehicle id and mount come from the scenario
  aggregator::AggregatorOptions aggregator;
  // Vehicles start localized around their true start pose with this uncertainty.
  double initial_sigma_xy_m = 0.05;
  double initial_sigma_theta_rad = 0.02;
  double divergence_period_s = 0.2;  // recorded DivergenceSamples per vehicle
  double pose_period_s = 1.0;        // recorded PoseSamples per vehicle
};

core::Result<std::unique_ptr<Pipeline>> MakeAgentsPipeline(
    const sim::World& world, const AgentsPipelineOptions& options = {});

}  // namespace fleetmap::eval
