// fleetmap-publish-samples: publishes one made-up message of every fleetmap LCM type on its
// channel, periodically, so that lcm-spy (ops/spy/fleetmap-spy) and loggers can be checked without
// a running fleet. The values are plausible but synthetic; map tile payloads are placeholder cell
// bytes, not codec frames. See docs/lcm_spy.md.

#include <zlib.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <lcm/lcm-cpp.hpp>
#include <optional>
#include <string>
#include <thread>

#include "core/command_line.h"
#include "fleetmap/divergence_t.hpp"
#include "fleetmap/laser_scan_t.hpp"
#include "fleetmap/map_delta_t.hpp"
#include "fleetmap/map_keyframe_t.hpp"
#include "fleetmap/map_request_t.hpp"
#include "fleetmap/merge_report_t.hpp"
#include "fleetmap/odometry_t.hpp"
#include "fleetmap/pose_with_covariance_t.hpp"
#include "fleetmap/status_t.hpp"
#include "fleetmap/tempmap_ack_t.hpp"
#include "fleetmap/tempmap_tile_t.hpp"
#include "lcmtypes/channels.h"

namespace fleetmap::ops::spy {
namespace {

volatile std::sig_atomic_t g_stop = 0;  // set by SIGINT/SIGTERM
void OnSignal(int) { g_stop = 1; }

struct Options {
  std::string lcm_url = "udpm://239.255.76.67:7667?ttl=0";  // LCM provider URL
  int count = 0;                                            // rounds to publish; 0: until SIGINT
  int period_ms = 200;                                      // time between rounds, milliseconds
};

// Reads the command line into `options`. No value: go on; otherwise the exit status.
std::optional<int> ParseArgs(int argc, char** argv, Options* options) {
  CLI::App app(
      "Publishes one sample of every fleetmap LCM type per round, for lcm-spy\n"
      "(docs/lcm_spy.md), until Ctrl-C or --count rounds.\n"
      "Exit status: 0 after the last round or a stop, 1 no LCM, 2 usage errors.",
      "fleetmap-publish-samples");
  core::AddVersionFlag(app);
  app.add_option("--lcm-url", options->lcm_url, "the LCM group")->capture_default_str();
  app.add_option("--count", options->count, "rounds to publish; 0: until SIGINT")
      ->check(CLI::Range(0, 1000000000))
      ->capture_default_str();
  app.add_option("--period-ms", options->period_ms, "time between rounds, milliseconds")
      ->check(CLI::Range(1, 3600000))
      ->capture_default_str();
  return core::ParseCommandLine(app, argc, argv);
}

int64_t NowUtime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

pose2d_t Pose(double x_m, double y_m, double theta_rad) {
  pose2d_t p;
  p.x_m = x_m;
  p.y_m = y_m;
  p.theta_rad = theta_rad;
  return p;
}

// A 32 x 32 tile of placeholder cells, one byte each: free (1) with an occupied (2) diagonal.
map_tile_t SampleTile(int round) {
  map_tile_t t;
  t.tile_x = 2;
  t.tile_y = 1;
  t.x0_cells = 64;
  t.y0_cells = 32;
  t.width_cells = 32;
  t.height_cells = 32;
  t.tile_version = round;
  t.codec = map_tile_t::PACKING_TRISTATE_8BIT | map_tile_t::COMPRESSION_NONE;
  t.payload.assign(32 * 32, 1);
  for (int i = 0; i < 32; ++i) t.payload[i * 32 + i] = 2;
  t.payload_size = static_cast<int32_t>(t.payload.size());
  t.crc32 = static_cast<int32_t>(crc32(0L, t.payload.data(), t.payload.size()));
  return t;
}

laser_scan_t SampleScan(int64_t utime, int round) {
  laser_scan_t s;
  s.utime = utime;
  s.vehicle_id = "agv_1";
  s.seq = round;
  s.angle_min_rad = static_cast<float>(-0.75 * M_PI);
  s.angle_increment_rad = static_cast<float>(M_PI / 360.0);
  s.range_min_m = 0.05f;
  s.range_max_m = 30.0f;
  s.scan_period_s = 0.04f;
  for (int i = 0; i < 541; ++i) s.ranges_m.push_back(4.0f + 0.5f * std::sin(0.05f * (i + round)));
  s.num_ranges = static_cast<int32_t>(s.ranges_m.size());
  s.num_intensities = 0;
  return s;
}

divergence_t SampleDivergence(int64_t utime, int round) {
  divergence_t d;
  d.utime = utime;
  d.vehicle_id = "agv_1";
  d.w_slow = 0.04;
  d.w_fast = 0.04 * (0.75 + 0.25 * std::cos(0.1 * round));
  d.w_avg = d.w_fast;
  d.d = std::max(0.0, 1.0 - d.w_fast / d.w_slow);
  d.state = d.d > 0.1 ? divergence_t::BUILDING : divergence_t::FREE;
  d.rotating = 0;
  d.tempmap_seq = 3;
  return d;
}

merge_report_t SampleMergeReport(int64_t utime, int round) {
  merge_report_t r;
  r.utime = utime;
  r.vehicle_id = "agv_1";
  r.tempmap_seq = 3;
  r.accepted = 1;
  r.dtheta_rad = 0.012;
  r.dx_m = -0.04;
  r.dy_m = 0.03;
  r.score = 0.86;
  for (int i = 0; i < 3; ++i) {
    line_match_t m;
    m.temp_line_id = i;
    m.static_line_id = 10 + i;
    m.distance_diff_px = 0.5 * i;
    m.angle_diff_deg = 0.2 * i;
    r.matches.push_back(m);
  }
  r.num_matches = static_cast<int32_t>(r.matches.size());
  r.cells_added = 120;
  r.cells_removed = 14;
  r.new_version = round;
  return r;
}

void PublishRound(lcm::LCM& lcm, int round) {
  const int64_t utime = NowUtime();
  const laser_scan_t scan = SampleScan(utime, round);
  lcm.publish(lcmtypes::ScanChannel("agv_1"), &scan);

  odometry_t odom;
  odom.utime = utime;
  odom.vehicle_id = "agv_1";
  odom.pose = Pose(0.1 * round, 2.0, 0.0);
  odom.v_mps = 0.5;
  odom.omega_radps = 0.0;
  lcm.publish(lcmtypes::OdomChannel("agv_1"), &odom);

  pose_with_covariance_t pose;
  pose.utime = utime;
  pose.vehicle_id = "agv_1";
  pose.pose = Pose(10.0 + 0.1 * round, 5.0, 0.02);
  for (int i = 0; i < 9; ++i) pose.covariance[i] = (i % 4 == 0) ? 0.01 : 0.0;
  pose.map_version = round;
  lcm.publish(lcmtypes::PoseChannel("agv_1"), &pose);

  const divergence_t divergence = SampleDivergence(utime, round);
  lcm.publish(lcmtypes::DivergenceChannel("agv_1"), &divergence);

  tempmap_tile_t temp;
  temp.utime = utime;
  temp.vehicle_id = "agv_1";
  temp.tempmap_seq = 3;
  temp.tile_index = 0;
  temp.tile_count = 1;
  temp.anchor_pose = Pose(12.0, 4.0, 0.0);
  temp.has_anchor_covariance = true;  // 2 cm and 1 degree
  std::fill(std::begin(temp.anchor_covariance), std::end(temp.anchor_covariance), 0.0);
  temp.anchor_covariance[0] = temp.anchor_covariance[4] = 4e-4;  // x, y
  temp.anchor_covariance[8] = 3e-4;                              // heading
  temp.grid_origin = Pose(-0.8, -0.8, 0.0);
  temp.resolution_m = 0.05f;
  temp.width_cells = 32;
  temp.height_cells = 32;
  temp.start_utime = utime - 2000000;
  temp.end_utime = utime;
  temp.tile = SampleTile(round);
  lcm.publish(lcmtypes::TempMapChannel("agv_1"), &temp);

  tempmap_ack_t ack;
  ack.utime = utime;
  ack.vehicle_id = "agv_1";
  ack.tempmap_seq = 3;
  ack.tile_count = 1;
  ack.received_tiles = {0};
  ack.num_received = 1;
  ack.outcome = tempmap_ack_t::MERGED;
  ack.map_version = round;
  lcm.publish(lcmtypes::kTempMapAckChannel, &ack);

  map_delta_t delta;
  delta.utime = utime;
  delta.base_version = round - 1;
  delta.new_version = round;
  delta.tile_index = 0;
  delta.tile_count = 1;
  delta.tile = SampleTile(round);
  lcm.publish(lcmtypes::kMapDeltaChannel, &delta);

  map_keyframe_t keyframe;
  keyframe.utime = utime;
  keyframe.version = round;
  keyframe.resolution_m = 0.05f;
  keyframe.width_cells = 128;
  keyframe.height_cells = 64;
  keyframe.origin = Pose(0.0, 0.0, 0.0);
  keyframe.tile_size_cells = 32;
  keyframe.tile_index = 6;
  keyframe.tile_count = 8;
  keyframe.tile = SampleTile(round);
  lcm.publish(lcmtypes::kMapKeyframeChannel, &keyframe);

  map_request_t request;
  request.utime = utime;
  request.vehicle_id = "agv_2";
  request.have_version = round - 2;
  request.num_tiles = 0;
  lcm.publish(lcmtypes::kMapRequestChannel, &request);

  const merge_report_t report = SampleMergeReport(utime, round);
  lcm.publish(lcmtypes::kMergeReportChannel, &report);

  status_t status;
  status.utime = utime;
  status.process = "publish_samples";
  status.software_version = "0.1.0";
  status.map_version = round;
  status.state = "running";
  status.authenticated = 0;
  status.counter_names = {"rounds"};
  status.counter_values = {round};
  status.num_counters = 1;
  lcm.publish(lcmtypes::StatusChannel("publish_samples"), &status);
}

int Run(int argc, char** argv) {
  Options options;
  if (const auto exit_status = ParseArgs(argc, argv, &options)) return *exit_status;
  lcm::LCM lcm(options.lcm_url);
  if (!lcm.good()) {
    std::fprintf(stderr, "cannot open LCM at %s (multicast route? see docs/lcm_spy.md)\n",
                 options.lcm_url.c_str());
    return 1;
  }
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  for (int round = 1; !g_stop && (options.count == 0 || round <= options.count); ++round) {
    PublishRound(lcm, round);
    std::this_thread::sleep_for(std::chrono::milliseconds(options.period_ms));
  }
  return 0;
}

}  // namespace
}  // namespace fleetmap::ops::spy

int main(int argc, char** argv) { return fleetmap::ops::spy::Run(argc, argv); }
