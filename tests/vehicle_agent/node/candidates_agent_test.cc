// The candidate watch at the agent's edge: MAP_CANDIDATES put together from its parts, and
// the candidates the vehicle's scans pass through sent back as CANDIDATES_FREE_<id>.
#include <gtest/gtest.h>

#include <algorithm>

#include "fleetmap/candidates_free_t.hpp"
#include "fleetmap/candidates_held_t.hpp"
#include "fleetmap/map_candidates_t.hpp"
#include "tests/vehicle_agent/node/node_test_util.h"
#include "vehicle_agent/node/candidate_parts.h"

namespace fleetmap::vehicle_agent::node {
namespace {

using testing::RecordingPublisher;

fleetmap::map_candidates_t Part(int64_t utime, int16_t part, int16_t parts,
                                std::vector<int32_t> cells) {
  fleetmap::map_candidates_t m;
  m.utime = utime;
  m.map_version = 3;
  m.part = part;
  m.parts = parts;
  m.cells = std::move(cells);
  m.num_cells = static_cast<int32_t>(m.cells.size());
  return m;
}

TEST(CandidatePartsTest, TheSetIsUsedOnceEveryPartOfOneSendingIsIn) {
  CandidateParts parts;
  auto r = parts.Add(Part(10, 1, 2, {7, 8}));
  ASSERT_TRUE(r.ok());
  EXPECT_FALSE(r->has_value());
  r = parts.Add(Part(20, 0, 2, {1}));  // a newer sending: the older part is dropped
  ASSERT_TRUE(r.ok());
  EXPECT_FALSE(r->has_value());
  r = parts.Add(Part(20, 1, 2, {5, 6}));
  ASSERT_TRUE(r.ok() && r->has_value());
  EXPECT_EQ(**r, (std::vector<int64_t>{1, 5, 6}));
  r = parts.Add(Part(30, 0, 0, {}));  // no candidates any more
  ASSERT_TRUE(r.ok() && r->has_value());
  EXPECT_TRUE((*r)->empty());
  EXPECT_FALSE(parts.Add(Part(40, 2, 2, {1})).ok());
  EXPECT_FALSE(parts.Add(Part(40, 0, 1, {-4})).ok());
}

int32_t CellAt(const core::GridGeometry& g, double x, double y) {
  return static_cast<int32_t>(g.Index(g.WorldToCell({x, y})));
}

// The vehicle crosses the room past a pallet standing from the start: two floor cells on its
// way are candidates (a person who turned there, gone), and so is a cell on the pallet's
// face. The floor cells are reported free after the scan times they were passed; the pallet's
// cell never.
TEST(CandidatesAgentTest, CandidatesTheScansPassThroughAreReportedFree) {
  const sim::World world = testing::RoomWorld(
      "[{id: pallet, rect: {center: [5.5, 4.2], size: [1.2, 0.8]}, appear_s: 0}]", 8.0);
  RecordingPublisher out;
  auto node =
      AgentNode::Create(testing::RoomOptions(world), &out, nullptr, world.static_map(), 0.0);
  ASSERT_TRUE(node.ok()) << node.status().ToString();
  const core::GridGeometry& g = world.static_map().geometry();
  const int32_t floor_a = CellAt(g, 4.0, 3.0), floor_b = CellAt(g, 6.5, 1.0);
  const int32_t pallet = CellAt(g, 5.5, 3.81);
  std::vector<int32_t> cells = {floor_a, floor_b, pallet};
  std::sort(cells.begin(), cells.end());
  testing::FeedMessage(**node, Link::kDownlink, lcmtypes::kMapCandidatesChannel,
                       Part(5, 0, 1, cells), 0.0);
  testing::DriveNode(world, **node, 8.0);

  const auto reports =
      out.Decoded<fleetmap::candidates_free_t>(lcmtypes::CandidatesFreeChannel("v1"));
  ASSERT_FALSE(reports.empty());
  std::vector<int32_t> reported;
  for (const auto& r : reports) {
    EXPECT_EQ(r.vehicle_id, "v1");
    EXPECT_LE(r.first_pass_utime, r.last_pass_utime);
    EXPECT_GE(r.first_pass_utime, 0);
    EXPECT_LE(r.last_pass_utime, lcmtypes::ToUtime(8.0));
    reported.insert(reported.end(), r.cells.begin(), r.cells.end());
  }
  std::sort(reported.begin(), reported.end());
  std::vector<int32_t> floor = {floor_a, floor_b};
  std::sort(floor.begin(), floor.end());
  EXPECT_EQ(reported, floor);  // each once, the pallet's never
  EXPECT_EQ(testing::Counter(**node, "seen_free_reports"), static_cast<int64_t>(reports.size()));

  // A MAP_CANDIDATES part that cannot be is counted and changes nothing.
  testing::FeedMessage(**node, Link::kDownlink, lcmtypes::kMapCandidatesChannel,
                       Part(6, 3, 1, {floor_a}), 8.0);
  EXPECT_EQ(testing::Counter(**node, "malformed_messages"), 1);
}

// The same drive: the beams keep ending at the pallet's face for seconds, and it is reported
// held (here after 3 s instead of the default 10, which the short drive does not last);
// the floor cells never are.
TEST(CandidatesAgentTest, ACandidateTheBeamsKeepEndingAtIsReportedHeld) {
  const sim::World world = testing::RoomWorld(
      "[{id: pallet, rect: {center: [5.5, 4.2], size: [1.2, 0.8]}, appear_s: 0}]", 8.0);
  RecordingPublisher out;
  AgentNodeOptions options = testing::RoomOptions(world);
  options.pipeline.candidate_watch.report_held_s = 3.0;
  auto node = AgentNode::Create(options, &out, nullptr, world.static_map(), 0.0);
  ASSERT_TRUE(node.ok()) << node.status().ToString();
  const core::GridGeometry& g = world.static_map().geometry();
  const int32_t floor_a = CellAt(g, 4.0, 3.0), pallet = CellAt(g, 5.5, 3.81);
  testing::FeedMessage(**node, Link::kDownlink, lcmtypes::kMapCandidatesChannel,
                       Part(5, 0, 1, {std::min(floor_a, pallet), std::max(floor_a, pallet)}), 0.0);
  testing::DriveNode(world, **node, 8.0);

  const auto reports =
      out.Decoded<fleetmap::candidates_held_t>(lcmtypes::CandidatesHeldChannel("v1"));
  ASSERT_EQ(reports.size(), 1u);
  const fleetmap::candidates_held_t& r = reports[0];
  EXPECT_EQ(r.vehicle_id, "v1");
  ASSERT_EQ(r.cells, std::vector<int32_t>{pallet});
  EXPECT_GE(r.until_ms[0] - r.since_ms[0], 3000);
  EXPECT_GE(r.base_utime, 0);
  EXPECT_EQ(testing::Counter(**node, "held_reports"), 1);
}

}  // namespace
}  // namespace fleetmap::vehicle_agent::node
