#include "sim/lcm_bridge/sim_publisher.h"

#include "lcmtypes/convert.h"

namespace fleetmap::sim::lcm_bridge {

SimPublisher::SimPublisher(lcm::LCM* lcm, const sim::World* world, SimPublisherOptions options)
    : lcm_(lcm), world_(world), options_(options) {}

template <typename Msg>
void SimPublisher::Send(const std::string& channel, const Msg& msg) {
  const int status = lcm_->publish(channel, &msg);
  ++counters_.messages;
  counters_.bytes += msg.getEncodedSize();
  if (status != 0) ++counters_.failures;
}

void SimPublisher::Publish(const sim::SimEvent& event) {
  const auto& vehicles = world_->scenario().vehicles;
  if (const auto* e = std::get_if<sim::ScanEvent>(&event)) {
    const std::string& id = vehicles[e->vehicle].id;
    core::LaserScan scan = e->scan;
    scan.stamp_s += options_.epoch_s;
    Send(lcmtypes::ScanChannel(id), lcmtypes::ToMessage(scan, id, scan_seq_[e->vehicle]++));
    if (options_.publish_truth) {
      core::PoseEstimate truth;
      truth.stamp_s = scan.stamp_s;
      truth.pose_in_map = e->true_base_pose;
      Send(lcmtypes::TruthChannel(id), lcmtypes::ToMessage(truth, id));
    }
  } else if (const auto* o = std::get_if<sim::OdometryEvent>(&event)) {
    const std::string& id = vehicles[o->vehicle].id;
    const core::OdometrySample odom{o->stamp_s + options_.epoch_s, o->odom_pose, o->v_mps,
                                    o->omega_radps};
    Send(lcmtypes::OdomChannel(id), lcmtypes::ToMessage(odom, id));
  } else if (const auto* p = std::get_if<sim::ExternalPoseEvent>(&event)) {
    const std::string& id = vehicles[p->vehicle].id;
    const sim::ExternalPoseNoise& n = vehicles[p->vehicle].external_pose;
    core::PoseEstimate pose;
    pose.stamp_s = p->stamp_s + options_.epoch_s;
    pose.pose_in_map = p->pose;
    pose.covariance.diagonal() << n.sigma_xy_m * n.sigma_xy_m, n.sigma_xy_m * n.sigma_xy_m,
        n.sigma_theta_rad * n.sigma_theta_rad;
    Send(lcmtypes::ExternalPoseChannel(id), lcmtypes::ToMessage(pose, id));
  }
}

}  // namespace fleetmap::sim::lcm_bridge
