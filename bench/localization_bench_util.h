// The worlds localization_bench and its studies drive: the LivingLab scenarios of
// sim/worlds/livinglab, and what one vehicle's sensors report while driving them. A world
// that does not load ends the program (exit status 1, the reason on stderr): a benchmark
// without its world measures nothing.
#pragma once

#include <string>
#include <vector>

#include "core/odometry.h"
#include "core/pose2.h"
#include "sim/simulator.h"

namespace fleetmap::bench {

// A scenario file of sim/worlds/livinglab.
sim::World LoadWorld(const std::string& scenario_file);

// A scenario written inline, on the LivingLab map.
sim::World ParseWorld(const std::string& yaml);

// What one vehicle's sensors reported, scan by scan, with the odometry sample before it.
struct SensorStep {
  core::OdometrySample odom;
  sim::ScanEvent scan;
};

// Vehicle `vehicle`'s scans of `world` up to simulated time `end_s`.
std::vector<SensorStep> RecordSensorSteps(const sim::World& world, size_t vehicle, double end_s);

// The addition route (addition.yaml), loaded once.
const sim::World& Addition();

// Where the scanner sits on the addition route's vehicle.
const core::Pose2& Mount();

}  // namespace fleetmap::bench
