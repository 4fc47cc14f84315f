// Runs a World forward in time and produces what the vehicles' sensors report: laser scans,
// wheel odometry and (optionally) external poses, in time order, deterministic for the
// scenario's seed. In-process and faster than real time: the program fleetmap-sim paces and
// publishes the same events over LCM.
#pragma once

#include <array>
#include <optional>
#include <random>
#include <variant>

#include "core/map/ray_caster.h"
#include "core/scan.h"
#include "sim/observation_log.h"
#include "sim/world.h"

namespace fleetmap::sim {

struct ScanEvent {
  size_t vehicle = 0;
  core::LaserScan scan;        // in the scanner frame; no return = +infinity
  core::Pose2 true_base_pose;  // ground truth, for evaluation and tests only
  core::Pose2 true_scanner_pose;
};

struct OdometryEvent {
  size_t vehicle = 0;
  double stamp_s = 0.0;
  core::Pose2 odom_pose;  // integrated noisy odometry, in the odometry frame (starts at 0)
  double v_mps = 0.0;
  double omega_radps = 0.0;
  core::Pose2 true_base_pose;
};

struct ExternalPoseEvent {
  size_t vehicle = 0;
  double stamp_s = 0.0;
  core::Pose2 pose;  // noisy pose in the map frame
};

using SimEvent = std::variant<ScanEvent, OdometryEvent, ExternalPoseEvent>;
double EventTime(const SimEvent& event);

class Simulator {
 public:
  explicit Simulator(const World* world);  // `world` outlives the simulator

  // The next event in time order, or nothing once the scenario's duration is over.
  std::optional<SimEvent> Next();
  double now_s() const { return now_s_; }
  const World& world() const { return *world_; }
  const ObservationLog& observations() const { return observations_; }
  size_t scans_produced() const { return scans_produced_; }

 private:
  struct VehicleClock {
    double next_scan_s, next_odom_s, next_external_s;
    core::Pose2 last_true_pose, odom_pose;
    std::mt19937 rng;
    double odom_scale = 1.0, odom_heading_drift_rad_m = 0.0;  // the systematic odometry error
  };
  ScanEvent MakeScan(size_t v, double t);
  OdometryEvent MakeOdometry(size_t v, double t);
  ExternalPoseEvent MakeExternalPose(size_t v, double t);
  void UpdateSolid(double t);
  double CastActors(const Eigen::Vector2d& origin, double angle, double range, double t) const;
  void RecordBeam(size_t v, const Eigen::Vector2d& origin, double angle, const core::RayHit& hit,
                  double range, double t);
  void ApplyScannerNoise(const ScannerModel& model, std::mt19937& rng,
                         std::vector<float>& ranges) const;

  const World* world_;
  core::RayCaster caster_;
  ObservationLog observations_;
  std::vector<VehicleClock> clocks_;
  std::vector<double> change_times_;
  size_t next_change_ = 0;
  double now_s_ = 0.0;
  size_t scans_produced_ = 0;
  std::vector<std::array<int, 4>> object_boxes_;  // cell bounding box per object: x0 y0 x1 y1
};

}  // namespace fleetmap::sim
