// What the agent sends: the channels and links, signed as the vehicle, stamped with wall time,
// the candidates in as many messages as their cells need, and refusals counted.
#include "vehicle_agent/node/agent_sender.h"

#include <gtest/gtest.h>

#include "auth/trailer.h"
#include "auth/verifier.h"
#include "fleetmap/candidates_free_t.hpp"
#include "fleetmap/candidates_held_t.hpp"
#include "fleetmap/divergence_t.hpp"
#include "fleetmap/map_request_t.hpp"
#include "fleetmap/pose_with_covariance_t.hpp"
#include "fleetmap/status_t.hpp"
#include "lcmtypes/convert.h"
#include "tests/edge/recording_publisher.h"

namespace fleetmap::vehicle_agent::node {
namespace {

using edge::testing::Payload;
using edge::testing::RecordingPublisher;
using edge::testing::SentMessage;

class AgentSenderTest : public ::testing::Test {
 protected:
  AgentSenderTest() : log_([this](LogLevel, const std::string& l) { lines_.push_back(l); }) {
    options_.pipeline.vehicle_id = "v1";
    options_.software_version = "9.9";
    options_.utime_offset_s = 1000.0;
  }
  AgentSender& Sender() {
    sender_ = std::make_unique<AgentSender>(options_, &out_, &log_, &counters_);
    return *sender_;
  }

  AgentNodeOptions options_;
  RecordingPublisher out_;
  std::vector<std::string> lines_;
  CauseLog log_;
  AgentNodeCounters counters_;
  std::unique_ptr<AgentSender> sender_;
};

TEST_F(AgentSenderTest, APoseAndItsDivergenceGoOnThePoseLinkStampedAsTheScan) {
  options_.pose_link = Link::kSensor;
  AgentSender& sender = Sender();
  core::LaserScan scan;
  scan.stamp_s = 12.5;
  AgentStep step;
  step.pose.stamp_s = 12.5;
  step.pose.pose_in_map = core::Pose2(4.0, 3.0, 0.25);
  step.building = true;
  step.divergence.d = 0.7;
  sender.SendStep(scan, step, 42);
  ASSERT_EQ(out_.sent.size(), 2u);
  EXPECT_EQ(out_.sent[0].link, Link::kSensor);
  EXPECT_EQ(out_.sent[0].channel, "POSE_v1");
  EXPECT_DOUBLE_EQ(Payload<fleetmap::pose_with_covariance_t>(out_.sent[0]).pose.x_m, 4.0);
  EXPECT_EQ(out_.sent[1].link, Link::kSensor);
  EXPECT_EQ(out_.sent[1].channel, "DIVERGENCE_v1");
  const auto d = Payload<fleetmap::divergence_t>(out_.sent[1]);
  EXPECT_EQ(d.tempmap_seq, 42);
  EXPECT_EQ(d.utime, lcmtypes::ToUtime(12.5));  // the scan's time, not the node's
  EXPECT_EQ(d.state, fleetmap::divergence_t::BUILDING);
  EXPECT_EQ(counters_.publish_failures, 0);
}

TEST_F(AgentSenderTest, CandidatesGoInAsManyMessagesAsTheirCellsNeedFreeBeforeHeld) {
  AgentSender& sender = Sender();
  sender.SendCandidates({}, {}, 3, 1.0);
  EXPECT_TRUE(out_.sent.empty());  // nothing seen: nothing sent

  CandidatesSeenFree seen;
  for (int64_t c = 0; c < 700; ++c) seen.cells.push_back(10 * c);
  seen.first_pass_s = 0.5, seen.last_pass_s = 0.9;
  CandidatesHeld held;
  for (int64_t c = 0; c < 150; ++c) {
    held.cells.push_back(c);
    held.since_s.push_back(0.2);
    held.until_s.push_back(0.7);
  }
  sender.SendCandidates(seen, held, 3, 1.0);
  ASSERT_EQ(out_.sent.size(), 5u);
  std::vector<int32_t> free_cells;
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(out_.sent[i].channel, "CANDIDATES_FREE_v1");
    EXPECT_EQ(out_.sent[i].link, Link::kUplink);
    const auto m = Payload<fleetmap::candidates_free_t>(out_.sent[i]);
    EXPECT_EQ(m.map_version, 3);
    EXPECT_EQ(m.utime, lcmtypes::ToUtime(1001.0));  // the node's clock carried to wall time
    EXPECT_EQ(m.first_pass_utime, lcmtypes::ToUtime(0.5));
    free_cells.insert(free_cells.end(), m.cells.begin(), m.cells.end());
  }
  EXPECT_EQ(Payload<fleetmap::candidates_free_t>(out_.sent[2]).num_cells, 100);
  ASSERT_EQ(free_cells.size(), 700u);
  EXPECT_EQ(free_cells[699], 6990);
  EXPECT_EQ(out_.sent[3].channel, "CANDIDATES_HELD_v1");
  EXPECT_EQ(out_.sent[4].channel, "CANDIDATES_HELD_v1");
  EXPECT_EQ(Payload<fleetmap::candidates_held_t>(out_.sent[4]).num_cells, 50);
  EXPECT_EQ(counters_.seen_free_reports, 3);
  EXPECT_EQ(counters_.held_reports, 2);
}

TEST_F(AgentSenderTest, WithAFleetKeyEverythingIsSignedAsTheVehicle) {
  const auth::Key key = auth::GenerateKey();
  options_.fleet_key = key;
  AgentSender& sender = Sender();
  sender.SendMapRequest(-1, {3, 7}, 2.0);
  sender.SendStatus(7, "running", {{"scans", 12}}, /*authenticated=*/true, 2.0);
  ASSERT_EQ(out_.sent.size(), 2u);
  auth::Verifier verifier(key);
  for (const SentMessage& s : out_.sent) {
    auth::Opened opened;
    EXPECT_EQ(
        verifier.Open(s.channel, s.bytes.data(), static_cast<int>(s.bytes.size()), "v1", &opened),
        auth::Verdict::kAccepted)
        << s.channel;
  }
  EXPECT_EQ(out_.sent[0].channel, "MAP_REQUEST");
  const auto request = Payload<fleetmap::map_request_t>(out_.sent[0]);
  EXPECT_EQ(request.have_version, -1);
  EXPECT_EQ(request.tiles, (std::vector<int32_t>{3, 7}));
  EXPECT_EQ(request.num_tiles, 2);
  EXPECT_EQ(out_.sent[1].channel, "STATUS_agent_v1");
  const auto status = Payload<fleetmap::status_t>(out_.sent[1]);
  EXPECT_EQ(status.process, "agent_v1");
  EXPECT_EQ(status.software_version, "9.9");
  EXPECT_EQ(status.map_version, 7);
  EXPECT_EQ(status.state, "running");
  EXPECT_TRUE(status.authenticated);
  EXPECT_EQ(status.utime, lcmtypes::ToUtime(1002.0));
  ASSERT_EQ(status.num_counters, 1);
  EXPECT_EQ(status.counter_values[0], 12);

  // Signed by another key, nothing is accepted.
  auth::Verifier stranger(auth::GenerateKey());
  auth::Opened opened;
  EXPECT_NE(stranger.Open(out_.sent[0].channel, out_.sent[0].bytes.data(),
                          static_cast<int>(out_.sent[0].bytes.size()), "v1", &opened),
            auth::Verdict::kAccepted);
}

TEST_F(AgentSenderTest, ARefusedMessageIsCountedAndLoggedOncePerChannel) {
  out_.accept = false;
  AgentSender& sender = Sender();
  std::vector<core::TempMapTile> tiles(3);
  for (int i = 0; i < 3; ++i) tiles[i].sequence = 5, tiles[i].index = i, tiles[i].count = 3;
  sender.SendTiles(tiles, 1.0);
  sender.SendMapRequest(4, {}, 1.0);
  EXPECT_EQ(out_.sent.size(), 4u);  // each was tried
  EXPECT_EQ(out_.sent[0].channel, "TEMPMAP_v1");
  EXPECT_EQ(counters_.publish_failures, 4);
  ASSERT_EQ(lines_.size(), 2u);
  const std::string once = " (logged once; later ones are only counted, in STATUS)";
  EXPECT_EQ(lines_[0], "cannot publish on TEMPMAP_v1 (uplink)" + once);
  EXPECT_EQ(lines_[1], "cannot publish on MAP_REQUEST (uplink)" + once);
}

}  // namespace
}  // namespace fleetmap::vehicle_agent::node
