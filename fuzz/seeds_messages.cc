// Seeds of the LCM message targets: real laser scans (SICK recordings, CARMEN logs) and the
// poses of CARMEN's odometry as our processes would publish them, plus one plausible message
// of every other type.
#include "fleetmap/divergence_t.hpp"
#include "fleetmap/map_request_t.hpp"
#include "fleetmap/merge_report_t.hpp"
#include "fleetmap/status_t.hpp"
#include "fleetmap/tempmap_ack_t.hpp"
#include "fuzz/lcm_bytes.h"
#include "fuzz/seed_sources.h"
#include "lcmtypes/convert.h"

namespace fleetmap::fuzz {
namespace {

core::LaserScan SyntheticScan() {
  core::LaserScan scan;
  scan.stamp_s = 1700000000.25;
  scan.angle_min_rad = -2.35619449;
  scan.angle_increment_rad = 0.00872664626;
  scan.range_max_m = 30.0;
  scan.range_min_m = 0.05;
  scan.scan_period_s = 0.04;
  for (int i = 0; i < 541; ++i) {
    scan.ranges_m.push_back(i % 50 == 0 ? std::numeric_limits<float>::infinity() : 3.0f + i % 7);
    scan.intensities.push_back(static_cast<float>(i % 255));
  }
  return scan;
}

void AddScans(SeedCorpus& corpus, const std::vector<core::LaserScan>& real_scans) {
  corpus.Add("lcm_laser_scan", "synthetic_s300_rssi",
             EncodeLcm(lcmtypes::ToMessage(SyntheticScan(), "vehicle_a", 1)));
  for (size_t i = 0; i < real_scans.size(); ++i) {
    corpus.Add("lcm_laser_scan", "real_scan" + std::to_string(i),
               EncodeLcm(lcmtypes::ToMessage(real_scans[i], "vehicle_b", int32_t(i))));
  }
}

void AddPoses(SeedCorpus& corpus) {
  const core::OdometrySample odom{1700000000.5, core::Pose2(4.78, -5.84, -1.69), 0.4, -0.1};
  corpus.Add("lcm_odometry", "moving", EncodeLcm(lcmtypes::ToMessage(odom, "vehicle_a")));
  core::PoseEstimate pose;
  pose.stamp_s = 1700000000.5;
  pose.pose_in_map = core::Pose2(12.0, 4.0, 3.1);
  pose.covariance << 0.01, 0.001, 0, 0.001, 0.02, 0, 0, 0, 0.003;
  pose.map_version = 5;
  corpus.Add("lcm_pose", "localized", EncodeLcm(lcmtypes::ToMessage(pose, "vehicle_a")));
}

void AddOtherMessages(SeedCorpus& corpus) {
  fleetmap::divergence_t d{};
  d.vehicle_id = "vehicle_a";
  d.w_avg = d.w_fast = 0.03;
  d.w_slow = 0.04;
  d.d = 0.25;
  d.state = fleetmap::divergence_t::BUILDING;
  corpus.Add("lcm_messages", "divergence", EncodeLcm(d));
  fleetmap::map_request_t request{};
  request.vehicle_id = "vehicle_a";
  request.have_version = 3;
  request.tiles = {0, 5, 17};
  request.num_tiles = 3;
  corpus.Add("lcm_messages", "map_request", EncodeLcm(request));
  fleetmap::merge_report_t report{};
  report.vehicle_id = "vehicle_a";
  report.reason = "too few line matches";
  report.matches.resize(2);
  report.num_matches = 2;
  corpus.Add("lcm_messages", "merge_report", EncodeLcm(report));
  fleetmap::status_t status{};
  status.process = "aggregator";
  status.software_version = "0.1.0";
  status.state = "running";
  status.counter_names = {"merges", "rejected_tiles"};
  status.counter_values = {12, 3};
  status.num_counters = 2;
  corpus.Add("lcm_messages", "status", EncodeLcm(status));
  fleetmap::tempmap_ack_t ack{};
  ack.vehicle_id = "vehicle_a";
  ack.tile_count = 4;
  ack.received_tiles = {0, 2};
  ack.num_received = 2;
  ack.outcome = fleetmap::tempmap_ack_t::PENDING;
  corpus.Add("lcm_messages", "tempmap_ack", EncodeLcm(ack));
  fleetmap::map_tile_t tile{};
  tile.payload = {1, 2, 3};
  tile.payload_size = 3;
  corpus.Add("lcm_messages", "map_tile", EncodeLcm(tile));
  corpus.Add("lcm_messages", "pose2d", EncodeLcm(lcmtypes::ToMessage(core::Pose2(1, 2, 3))));
  corpus.Add("lcm_messages", "line_match", EncodeLcm(fleetmap::line_match_t{}));
}

}  // namespace

void AddMessageSeeds(SeedCorpus& corpus, const std::vector<core::LaserScan>& real_scans) {
  AddScans(corpus, real_scans);
  AddPoses(corpus);
  AddOtherMessages(corpus);
}

}  // namespace fleetmap::fuzz
