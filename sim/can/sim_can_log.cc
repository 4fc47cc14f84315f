#include "sim/can/sim_can_log.h"

#include "drivers/can/diff_drive_can_encoder.h"
#include "sim/simulator.h"

namespace fleetmap::sim::can {

core::Status SimCanLogOptions::Validate() const {
  if (!(duration_s >= 0.0)) return core::InvalidArgument("sim_can_log.duration_s must be >= 0");
  if (interface.empty()) return core::InvalidArgument("sim_can_log.interface is empty");
  return can.Validate();
}

core::Result<SimCanLog> RecordOdometryAsCan(const sim::World& world,
                                            const SimCanLogOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  if (options.vehicle >= world.scenario().vehicles.size()) {
    return core::InvalidArgument("sim_can_log.vehicle " + std::to_string(options.vehicle) +
                                 " does not exist in " + world.scenario().name);
  }
  const double end_s = options.duration_s > 0.0 ? options.duration_s : world.scenario().duration_s;
  sim::Simulator simulator(&world);
  drivers::can::DiffDriveCanEncoder encoder(options.can, options.start_ticks);
  SimCanLog log;
  while (std::optional<sim::SimEvent> event = simulator.Next()) {
    if (sim::EventTime(*event) > end_s) break;
    const auto* odom = std::get_if<sim::OdometryEvent>(&*event);
    if (odom == nullptr || odom->vehicle != options.vehicle) continue;
    core::OdometrySample sample;
    sample.stamp_s = options.start_time_s + odom->stamp_s;
    sample.pose_in_odom = odom->odom_pose;
    sample.v_mps = odom->v_mps;
    sample.omega_radps = odom->omega_radps;
    for (drivers::can::CanFrame& frame : encoder.Encode(sample)) {
      log.records.push_back({options.interface, frame});
    }
    log.odometry.push_back(sample);
  }
  return log;
}

}  // namespace fleetmap::sim::can
