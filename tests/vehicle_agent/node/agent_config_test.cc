// The agent's configuration file and command line.
#include "vehicle_agent/node/agent_config.h"

#include <gtest/gtest.h>

#include "vehicle_agent/node/agent_flags.h"

namespace fleetmap::vehicle_agent::node {
namespace {

const std::string kExample =
    std::string(FLEETMAP_SOURCE_DIR) + "/vehicle_agent/node/fleetmap_agent.example.yaml";

// The example says it lists every key with its default (docs/agent_process.md): the tuning
// values in it are the code's, so that a deployer who copies it gets the measured behaviour.
// (It once kept 60 s temporary maps, 2 s divergence and a 5 s scanner reconnect long after
// the defaults became 3 s, 20 s and 0.5 s.)
TEST(AgentConfigTest, TheShippedExampleHoldsTheDefaults) {
  auto c = LoadAgentConfig(kExample);
  ASSERT_TRUE(c.ok()) << c.status().ToString();
  const AgentConfig d;
  const auto& lp = c->node.pipeline.localizer;
  const auto& ld = d.node.pipeline.localizer;
  EXPECT_EQ(lp.max_beams, ld.max_beams);
  EXPECT_EQ(lp.kld.min_particles, ld.kld.min_particles);
  EXPECT_EQ(lp.kld.max_particles, ld.kld.max_particles);
  EXPECT_DOUBLE_EQ(lp.update_min_translation_m, ld.update_min_translation_m);
  EXPECT_DOUBLE_EQ(lp.update_min_rotation_rad, ld.update_min_rotation_rad);
  EXPECT_EQ(lp.w_avg_model, ld.w_avg_model);
  EXPECT_EQ(lp.seed, ld.seed);
  EXPECT_DOUBLE_EQ(lp.odometry_scale.initial_sigma, ld.odometry_scale.initial_sigma);
  EXPECT_DOUBLE_EQ(lp.odometry_scale.walk_sigma_per_sqrt_m,
                   ld.odometry_scale.walk_sigma_per_sqrt_m);
  EXPECT_DOUBLE_EQ(lp.odometry_scale.pull_distance_m, ld.odometry_scale.pull_distance_m);
  const auto& dp = c->node.pipeline.divergence;
  const auto& dd = d.node.pipeline.divergence;
  EXPECT_EQ(dp.rule, dd.rule);
  EXPECT_DOUBLE_EQ(dp.start_above, dd.start_above);
  EXPECT_DOUBLE_EQ(dp.stop_below, dd.stop_below);
  EXPECT_DOUBLE_EQ(dp.min_duration_s, dd.min_duration_s);
  EXPECT_DOUBLE_EQ(dp.max_duration_s, dd.max_duration_s);
  EXPECT_EQ(dp.map_at_start, dd.map_at_start);
  const auto& bp = c->node.pipeline.builder;
  const auto& bd = d.node.pipeline.builder;
  EXPECT_DOUBLE_EQ(bp.mapper.map.size_m, bd.mapper.map.size_m);
  EXPECT_DOUBLE_EQ(bp.max_duration_s, bd.max_duration_s);
  EXPECT_DOUBLE_EQ(bp.edge_margin_m, bd.edge_margin_m);
  EXPECT_DOUBLE_EQ(bp.mapper.matcher.prior_sigma_xy_m, bd.mapper.matcher.prior_sigma_xy_m);
  EXPECT_DOUBLE_EQ(bp.mapper.matcher.prior_sigma_xy_per_m, bd.mapper.matcher.prior_sigma_xy_per_m);
  const auto& wp = c->node.pipeline.candidate_watch;
  const auto& wd = d.node.pipeline.candidate_watch;
  EXPECT_DOUBLE_EQ(wp.pass_margin_m, wd.pass_margin_m);
  EXPECT_DOUBLE_EQ(wp.hit_margin_m, wd.hit_margin_m);
  EXPECT_EQ(wp.min_free_scans, wd.min_free_scans);
  EXPECT_DOUBLE_EQ(wp.hold_gap_s, wd.hold_gap_s);
  EXPECT_DOUBLE_EQ(wp.report_held_s, wd.report_held_s);
  EXPECT_DOUBLE_EQ(wp.max_range_m, wd.max_range_m);
  EXPECT_DOUBLE_EQ(c->node.pipeline.candidate_watch_max_sigma_m,
                   d.node.pipeline.candidate_watch_max_sigma_m);
  EXPECT_DOUBLE_EQ(c->node.outbox.first_resend_s, d.node.outbox.first_resend_s);
  EXPECT_DOUBLE_EQ(c->node.outbox.max_resend_s, d.node.outbox.max_resend_s);
  EXPECT_EQ(c->node.outbox.max_pending_maps, d.node.outbox.max_pending_maps);
  EXPECT_EQ(c->node.map.tile_size_cells, d.node.map.tile_size_cells);
  EXPECT_EQ(c->node.map.max_buffered_versions, d.node.map.max_buffered_versions);
  EXPECT_DOUBLE_EQ(c->node.status_period_s, d.node.status_period_s);
  EXPECT_DOUBLE_EQ(c->node.map.request_period_s, d.node.map.request_period_s);
  EXPECT_EQ(c->node.queue.max_queued_scans, d.node.queue.max_queued_scans);
  EXPECT_DOUBLE_EQ(c->loop_wait_s, d.loop_wait_s);
  EXPECT_DOUBLE_EQ(c->shutdown_drain_s, d.shutdown_drain_s);
  EXPECT_DOUBLE_EQ(c->node.uplink_pacer.rate_per_s, d.node.uplink_pacer.rate_per_s);
  EXPECT_DOUBLE_EQ(c->node.uplink_pacer.burst, d.node.uplink_pacer.burst);
  const auto& sp = c->sick.client;
  const auto& sd = d.sick.client;
  EXPECT_DOUBLE_EQ(sp.connect_timeout_s, sd.connect_timeout_s);
  EXPECT_DOUBLE_EQ(sp.silence_timeout_s, sd.silence_timeout_s);
  EXPECT_DOUBLE_EQ(sp.first_scan_timeout_s, sd.first_scan_timeout_s);
  EXPECT_EQ(sp.start_measurement, sd.start_measurement);
  EXPECT_DOUBLE_EQ(sp.reconnect_backoff_initial_s, sd.reconnect_backoff_initial_s);
  EXPECT_DOUBLE_EQ(sp.reconnect_backoff_max_s, sd.reconnect_backoff_max_s);
  EXPECT_DOUBLE_EQ(c->sick.conversion.range_min_m, d.sick.conversion.range_min_m);
  EXPECT_DOUBLE_EQ(c->sick.conversion.range_max_m, d.sick.conversion.range_max_m);
}

TEST(AgentConfigTest, TheShippedExampleLoadsWithEveryValue) {
  auto c = LoadAgentConfig(kExample);
  ASSERT_TRUE(c.ok()) << c.status().ToString();
  EXPECT_TRUE(c->Validate().ok()) << c->Validate().ToString();
  EXPECT_EQ(c->node.pipeline.vehicle_id, "cts1");
  EXPECT_EQ(c->map_yaml, std::string(FLEETMAP_SOURCE_DIR) + "/sim/worlds/livinglab/livinglab.yaml");
  EXPECT_EQ(c->node.outbox.state_dir, "/var/lib/fleetmap/cts1");
  EXPECT_TRUE(c->final_map_yaml.empty());
  EXPECT_DOUBLE_EQ(c->node.pipeline.scanner_in_base.x_m, 0.3);
  EXPECT_EQ(c->node.initial_pose, InitialPoseSource::kGiven);
  EXPECT_DOUBLE_EQ(c->node.pipeline.localizer.initial_pose_in_map.x_m, 5.0);
  EXPECT_DOUBLE_EQ(c->node.pipeline.localizer.initial_sigma_theta_rad, 0.26);
  EXPECT_EQ(c->scan_source, ScanSource::kSick);
  EXPECT_EQ(c->odom_source, OdomSource::kCan);
  EXPECT_FALSE(c->node.scans_from_lcm);
  EXPECT_FALSE(c->node.odometry_from_lcm);
  EXPECT_EQ(c->sick.client.protocol, drivers::sick::ColaProtocol::kColaB);
  EXPECT_DOUBLE_EQ(c->sick.conversion.range_max_m, 80.0);
  EXPECT_DOUBLE_EQ(c->can.odometry.gear_ratio, 20.0);
  EXPECT_TRUE(c->can.odometry.right.inverted);
  EXPECT_EQ(c->can.socket.interface, "can0");
  EXPECT_EQ(c->node.pipeline.localizer.external_pose_mode, ExternalPoseMode::kFuse);
  EXPECT_EQ(c->urls.uplink, "udpm://239.255.76.67:7667?ttl=1&recv_buf_size=8388608");
  EXPECT_EQ(c->node.pose_link, Link::kUplink);
}

TEST(AgentConfigTest, DefaultsWithOnlyAVehicleId) {
  auto c = ParseAgentConfig("vehicle_id: v7\n", "/etc/fleetmap/agent.yaml");
  ASSERT_TRUE(c.ok()) << c.status().ToString();
  EXPECT_TRUE(c->Validate().ok());
  EXPECT_EQ(c->urls.sensor, "udpm://239.255.76.69:7669?ttl=0");
  EXPECT_EQ(c->scan_source, ScanSource::kLcm);
  EXPECT_TRUE(c->node.scans_from_lcm && c->node.odometry_from_lcm);
  EXPECT_EQ(c->node.initial_pose, InitialPoseSource::kGlobal);  // nothing said where
  EXPECT_TRUE(c->map_yaml.empty());
  EXPECT_DOUBLE_EQ(c->node.status_period_s, 1.0);
  auto external = ParseAgentConfig("vehicle_id: v7\ninputs: {external_pose: true}\n", "a.yaml");
  ASSERT_TRUE(external.ok());
  EXPECT_EQ(external->node.initial_pose, InitialPoseSource::kFirstExternal);
}

TEST(AgentConfigTest, TheOdometrysScaleIsLearntAsSet) {
  auto c = ParseAgentConfig(
      "vehicle_id: v7\nlocalization: {odometry_scale_sigma: 0.03, "
      "odometry_scale_walk_sigma_per_sqrt_m: 0.01, odometry_scale_pull_distance_m: 0}\n",
      "a.yaml");
  ASSERT_TRUE(c.ok()) << c.status().ToString();
  EXPECT_TRUE(c->Validate().ok()) << c->Validate().ToString();
  const OdometryScaleOptions& o = c->node.pipeline.localizer.odometry_scale;
  EXPECT_DOUBLE_EQ(o.initial_sigma, 0.03);
  EXPECT_DOUBLE_EQ(o.walk_sigma_per_sqrt_m, 0.01);
  EXPECT_EQ(o.pull_distance_m, 0.0);  // never pulled back
  auto negative = ParseAgentConfig(
      "vehicle_id: v7\nlocalization: {odometry_scale_pull_distance_m: -5}\n", "a.yaml");
  ASSERT_TRUE(negative.ok());  // read; refused by the check
  EXPECT_FALSE(negative->Validate().ok());
}

TEST(AgentConfigTest, TheMapAtStartUpCanBeSwitchedOn) {
  EXPECT_FALSE(
      ParseAgentConfig("vehicle_id: v7\n", "a.yaml")->node.pipeline.divergence.map_at_start);
  auto c = ParseAgentConfig("vehicle_id: v7\ndivergence: {map_at_start: true}\n", "a.yaml");
  ASSERT_TRUE(c.ok()) << c.status().ToString();
  EXPECT_TRUE(c->node.pipeline.divergence.map_at_start);
  EXPECT_FALSE(ParseAgentConfig("vehicle_id: v7\ndivergence: {map_at_start: 2}\n", "a.yaml").ok());
}

TEST(AgentConfigTest, MistakesAreErrorsThatNameTheKeyAndLine) {
  struct Case {
    const char* yaml;
    const char* says;
  };
  for (const Case& c : std::vector<Case>{
           {"vehicle_id: v1\nlocalisation: {max_beams: 3}\n",
            "a.yaml:2: localisation: unknown key"},
           {"vehicle_id: v1\ndivergence:\n  start_abov: 0.2\n",
            "divergence.start_abov: unknown key"},
           {"vehicle_id: v1\ninputs: {scan_source: usb}\n", "inputs.scan_source: must be one of"},
           {"vehicle_id: v1\nscanner_mount: [0.3, 0]\n", "scanner_mount: must have 3 numbers"},
           {"vehicle_id: v1\ninitial_pose: somewhere\n", "initial_pose: must be global"},
           {"vehicle_id: v1\ninitial_pose: {x_m: 1, y_m: 2}\n", "initial_pose.theta_rad: missing"},
           {"vehicle_id: v1\ninputs: {sick: {protocol: cola-c}}\n", "unknown CoLa protocol"},
           {"vehicle_id: v1\nrates: {status_period_s: fast}\n",
            "rates.status_period_s: has the wrong type"},
           {"vehicle_id: v1\ninputs: {can: {mapping: {wheel_radius_m: -1}}}\n", "wheel_radius_m"},
           {"vehicle_id: v1\ncandidate_watch: {margin_m: 0.2}\n",
            "candidate_watch.margin_m: unknown key"},
           {"vehicle_id: [v1\n", "a.yaml:"},
       }) {
    auto parsed = ParseAgentConfig(c.yaml, "a.yaml");
    ASSERT_FALSE(parsed.ok()) << c.yaml;
    EXPECT_NE(parsed.status().message().find(c.says), std::string::npos)
        << parsed.status().ToString();
  }
  // Values that parse but do not fit are refused by Validate with the key's name.
  for (const char* yaml : {"vehicle_id: v1\noutbox: {first_resend_s: 0}\n",
                           "vehicle_id: v1\nrates: {max_queued_scans: 0}\n",
                           "vehicle_id: v1\nrates: {loop_wait_s: 2}\n",
                           "vehicle_id: v1\nrates: {shutdown_drain_s: -1}\n",
                           "vehicle_id: v1\ninputs: {scan_source: sick, sick: {port: 0}}\n",
                           "vehicle_id: v1\ninitial_pose: external\n", "vehicle_id: 'v.1'\n",
                           "vehicle_id: v1\ncandidate_watch: {min_free_scans: 0}\n",
                           "vehicle_id: v1\ncandidate_watch: {max_sigma_m: 0}\n",
                           "vehicle_id: v1\ncandidate_watch: {hold_gap_s: 0}\n",
                           "vehicle_id: v1\nbuilder: {odometry_sigma_per_m: -0.01}\n"}) {
    auto parsed = ParseAgentConfig(yaml, "a.yaml");
    ASSERT_TRUE(parsed.ok()) << yaml << parsed.status().ToString();
    EXPECT_FALSE(parsed->Validate().ok()) << yaml;
  }
}

// The builder's matcher weighs each scan against the vehicle's odometry as the file says.
TEST(AgentConfigTest, TheOdometrysErrorSetsTheBuildersPrior) {
  auto parsed = ParseAgentConfig(
      "vehicle_id: v1\nbuilder: {odometry_sigma_m: 0.004, odometry_sigma_per_m: 0.05}\n", "a.yaml");
  ASSERT_TRUE(parsed.ok()) << parsed.status().ToString();
  const auto& matcher = parsed->node.pipeline.builder.mapper.matcher;
  EXPECT_DOUBLE_EQ(matcher.prior_sigma_xy_m, 0.004);
  EXPECT_DOUBLE_EQ(matcher.prior_sigma_xy_per_m, 0.05);
  EXPECT_TRUE(parsed->Validate().ok());
}

TEST(AgentFlagsTest, FlagsOverrideTheFileAndAreChecked) {
  auto c = ParseAgentCommandLine({"--config",       kExample,        "--vehicle-id",
                                  "cts2",           "--map",         "/maps/hall.yaml",
                                  "--initial-pose", "1.5,-2,0.25",   "--scanner-mount=0.35,0,0",
                                  "--state-dir",    "/tmp/st",       "--sensor-url",
                                  "memq://",        "--uplink-url",  "memq://",
                                  "--downlink-url", "memq://",       "--final-map",
                                  "out.yaml",       "--duration",    "12.5",
                                  "--sick",         "10.0.0.7:2111", "--quiet"});
  ASSERT_TRUE(c.ok()) << c.status().ToString();
  const AgentConfig& a = c->config;
  EXPECT_EQ(a.node.pipeline.vehicle_id, "cts2");
  EXPECT_EQ(a.map_yaml, "/maps/hall.yaml");
  EXPECT_DOUBLE_EQ(a.node.pipeline.localizer.initial_pose_in_map.y_m, -2.0);
  EXPECT_DOUBLE_EQ(a.node.pipeline.localizer.initial_pose_in_map.theta_rad, 0.25);
  EXPECT_DOUBLE_EQ(a.node.pipeline.scanner_in_base.x_m, 0.35);
  EXPECT_EQ(a.node.outbox.state_dir, "/tmp/st");
  EXPECT_EQ(a.urls.downlink, "memq://");
  EXPECT_EQ(a.final_map_yaml, "out.yaml");
  EXPECT_DOUBLE_EQ(a.duration_s, 12.5);
  EXPECT_EQ(a.sick.client.host, "10.0.0.7");
  EXPECT_EQ(a.sick.client.port, 2111);
  EXPECT_TRUE(a.quiet);
  // Without a file: what run_demo passes is enough.
  auto demo = ParseAgentCommandLine({"--vehicle-id", "v1", "--initial-pose", "5,4,0"});
  ASSERT_TRUE(demo.ok()) << demo.status().ToString();
  EXPECT_EQ(demo->config.node.initial_pose, InitialPoseSource::kGiven);
  EXPECT_TRUE(demo->config.node.scans_from_lcm);
  EXPECT_TRUE(ParseAgentCommandLine({"--help"})->help);
  EXPECT_TRUE(ParseAgentCommandLine({"--version"})->version);
  for (const std::vector<std::string>& bad :
       std::vector<std::vector<std::string>>{{"--vehicle-id"},
                                             {"--vehicle-id", "v1", "--frobnicate"},
                                             {"--vehicle-id", "v1", "--initial-pose", "1,2"},
                                             {"--vehicle-id", "v1", "--initial-pose", "1,2,x"},
                                             {"--vehicle-id", "v1", "--initial-pose", "1,2,3,4"},
                                             {"--vehicle-id", "v1", "--duration", "-1"},
                                             {"--vehicle-id", "v1", "--sick", "host"},
                                             {"--vehicle-id", "v1", "--sick", "host:99999"},
                                             {"--config", "/nonexistent.yaml"},
                                             {"--map", "m.yaml"}}) {
    EXPECT_FALSE(ParseAgentCommandLine(bad).ok()) << bad.back();
  }
}

}  // namespace
}  // namespace fleetmap::vehicle_agent::node
