// Bad input reaches the node on every channel: each is counted, logged once per cause, and
// never stops it or its pose.
#include <gtest/gtest.h>

#include <cmath>

#include "fleetmap/tempmap_ack_t.hpp"
#include "tests/vehicle_agent/node/node_test_util.h"

namespace fleetmap::vehicle_agent::node {
namespace {

using testing::RecordingPublisher;

class BadInputTest : public ::testing::Test {
 protected:
  BadInputTest() : world_(testing::RoomWorld()) {
    LogSink sink = [this](LogLevel level, const std::string& line) {
      if (level == LogLevel::kWarning) warnings_.push_back(line);
    };
    node_ = AgentNode::Create(testing::RoomOptions(world_), &out_, sink, world_.static_map(), 0.0)
                .value();
  }
  void Raw(Link link, const std::string& channel, std::vector<uint8_t> bytes) {
    testing::Feed(*node_, link, channel, bytes, 0.0);
  }
  template <typename T>
  void Send(Link link, const std::string& channel, const T& m) {
    testing::FeedMessage(*node_, link, channel, m, 0.0);
  }
  int64_t Counter(const std::string& name) const { return testing::Counter(*node_, name); }

  sim::World world_;
  RecordingPublisher out_;
  std::vector<std::string> warnings_;
  std::unique_ptr<AgentNode> node_;
};

TEST_F(BadInputTest, GarbageOnEveryChannelIsCountedAndLoggedOncePerCause) {
  const std::vector<uint8_t> garbage = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
  for (const Subscription& s : node_->Subscriptions()) {
    for (int i = 0; i < 5; ++i) Raw(s.link, s.channel, garbage);
  }
  Raw(Link::kSensor, "SCAN_v1", {});  // empty
  // A real scan cut short.
  core::LaserScan scan;
  scan.angle_increment_rad = 0.01;
  scan.range_max_m = 30;
  scan.ranges_m.assign(100, 2.0f);
  std::vector<uint8_t> cut = Encode(lcmtypes::ToMessage(scan, "v1", 0));
  cut.resize(cut.size() / 2);
  Raw(Link::kSensor, "SCAN_v1", cut);
  // Channels we never subscribed to are not ours to judge.
  Raw(Link::kSensor, "SCAN_v2", garbage);
  Raw(Link::kUplink, "TEMPMAP_v7", garbage);
  node_->Tick(0.1);
  const auto subs = static_cast<int64_t>(node_->Subscriptions().size());
  EXPECT_EQ(Counter("malformed_messages"), 5 * subs + 2);
  EXPECT_EQ(static_cast<int64_t>(warnings_.size()), subs);  // one per channel and cause
  EXPECT_EQ(node_->state(), "running");
}

TEST_F(BadInputTest, BadScansAndOdometryAreCountedAndThePoseStaysFinite) {
  sim::Simulator simulator(&world_);
  int32_t seq = 0;
  int scans = 0, foreign = 0;
  while (auto e = simulator.Next()) {
    if (sim::EventTime(*e) > 3.0) break;
    if (auto* o = std::get_if<sim::OdometryEvent>(&*e)) {
      auto m = lcmtypes::ToMessage(
          core::OdometrySample{o->stamp_s, o->odom_pose, o->v_mps, o->omega_radps}, "v1");
      if (seq % 10 == 3) m.pose.x_m = NAN;  // a broken sample now and then
      Send(Link::kSensor, "ODOM_v1", m);
    } else if (auto* s = std::get_if<sim::ScanEvent>(&*e)) {
      auto m = lcmtypes::ToMessage(s->scan, "v1", seq++);
      for (size_t i = 0; i < m.ranges_m.size(); i += 7) m.ranges_m[i] = NAN;    // NaN ranges
      if (seq % 10 == 5) m.vehicle_id = "v2", ++foreign;                        // someone else's
      if (seq % 10 == 6) m.num_intensities = 3, m.intensities.assign(3, 1.0f);  // inconsistent
      Send(Link::kSensor, "SCAN_v1", m);
      node_->Tick(s->scan.stamp_s);
      ++scans;
    }
  }
  EXPECT_GT(Counter("beams_invalid"), 1000);
  EXPECT_EQ(Counter("wrong_vehicle_messages"), foreign);
  EXPECT_GE(Counter("malformed_messages"), scans / 10 + 5);  // intensities and odometry
  EXPECT_GT(Counter("scans"), scans * 7 / 10);
  for (const auto& p : out_.Decoded<fleetmap::pose_with_covariance_t>("POSE_v1")) {
    EXPECT_TRUE(std::isfinite(p.pose.x_m) && std::isfinite(p.pose.y_m));
  }
}

TEST_F(BadInputTest, MapTilesThatDoNotFitAreRefusedAndCounted) {
  node_->Tick(0.0);
  // A keyframe of another geometry (another site's map).
  core::OccupancyGrid other(core::GridGeometry(0.05, 100, 100));
  for (const auto& m : testing::KeyframeMessages(other, 7))
    Send(Link::kDownlink, "MAP_KEYFRAME", m);
  EXPECT_GT(Counter("map_tiles_wrong_geometry"), 0);
  // A delta that claims to skip a version, one with a corrupt CRC.
  core::OccupancyGrid changed = world_.static_map();
  changed.SetState({50, 50}, core::CellState::kOccupied);
  auto delta = testing::DeltaMessages(world_.static_map(), changed, 0);
  auto skipping = delta[0];
  skipping.new_version = 5;
  Send(Link::kDownlink, "MAP_DELTA", skipping);
  auto corrupt = delta[0];
  corrupt.tile.crc32 ^= 1;
  Send(Link::kDownlink, "MAP_DELTA", corrupt);
  EXPECT_EQ(Counter("malformed_messages"), 2);
  // Deltas for versions far ahead of ours wait (and make the node ask); more than the replica
  // holds are refused.
  for (int32_t base = 100; base < 120; ++base)
    Send(Link::kDownlink, "MAP_DELTA", testing::DeltaMessages(changed, changed, base)[0]);
  EXPECT_GT(Counter("map_tiles_refused"), 0);
  const size_t mark = out_.sent.size();
  node_->Tick(1.5);
  EXPECT_EQ(out_.Count("MAP_REQUEST", mark), 1u);
  // Acks with an unknown outcome or impossible tile indices.
  fleetmap::tempmap_ack_t ack;
  ack.vehicle_id = "v1";
  ack.tempmap_seq = 1;
  ack.tile_count = 4;
  ack.num_received = 0;
  ack.outcome = 9;
  Send(Link::kDownlink, "TEMPMAP_ACK", ack);
  ack.outcome = fleetmap::tempmap_ack_t::PENDING;
  ack.received_tiles = {0, 7};
  ack.num_received = 2;
  Send(Link::kDownlink, "TEMPMAP_ACK", ack);
  EXPECT_EQ(Counter("malformed_messages"), 4);
  // Through all of it the map stayed version 0.
  node_->Tick(2.0);
  EXPECT_EQ(node_->map_version(), 0);
  EXPECT_EQ(node_->state(), "running");
}

TEST_F(BadInputTest, FallingBehindSkipsToTheNewestScanAndCountsTheRest) {
  sim::Simulator simulator(&world_);
  int32_t seq = 0, queued = 0;
  while (auto e = simulator.Next()) {
    const double t = sim::EventTime(*e);
    if (t > 3.0) break;
    if (auto* o = std::get_if<sim::OdometryEvent>(&*e)) {
      node_->OnDriverOdometry({o->stamp_s, o->odom_pose, o->v_mps, o->omega_radps});
    } else if (auto* s = std::get_if<sim::ScanEvent>(&*e)) {
      Send(Link::kSensor, "SCAN_v1", lcmtypes::ToMessage(s->scan, "v1", seq++));
      // Keeping up for 2 s, then one loop for the scans of a whole second.
      if (t < 2.0)
        node_->Tick(t);
      else
        ++queued;
    }
  }
  const int64_t before = Counter("scans");
  const size_t mark = out_.sent.size();
  node_->Tick(3.0);
  EXPECT_EQ(Counter("scans"), before + 1);
  EXPECT_EQ(Counter("scans_skipped"), queued - 1);
  const auto poses = out_.Decoded<fleetmap::pose_with_covariance_t>("POSE_v1", mark);
  ASSERT_EQ(poses.size(), 1u);
  // Every odometry sample was used: the one pose is where the vehicle is.
  const core::Pose2 truth = world_.VehicleStateAt(0, lcmtypes::FromUtime(poses[0].utime)).pose;
  EXPECT_LT(std::hypot(poses[0].pose.x_m - truth.x_m, poses[0].pose.y_m - truth.y_m), 0.05);
}

}  // namespace
}  // namespace fleetmap::vehicle_agent::node
