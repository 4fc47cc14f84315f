// Faults of the aggregator's environment (docs/reliability.md): a really full disk (a small
// tmpfs as the state folder) while it persists merges, and a vehicle whose clock jumps.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sched.h>
#include <sys/mount.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "tests/aggregator/node/node_test_util.h"
#include "tests/aggregator/test_files.h"

namespace fleetmap::aggregator::node {
namespace {

using testing::Feed;
using testing::LogLines;
using testing::MakeNode;
using testing::PalletMaps;
using testing::RecordingPublisher;
using testing::TileMessages;

constexpr int64_t kUtime = 1'700'000'000'000'000;

// Writes a file until the file system is full; returns its path.
std::string FillDisk(const std::string& folder) {
  const std::string path = folder + "/filler";
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  EXPECT_GE(fd, 0);
  std::vector<char> block(4096, 'x');
  while (::write(fd, block.data(), block.size()) > 0) {
  }
  EXPECT_EQ(errno, ENOSPC);
  ::close(fd);
  return path;
}

std::vector<fleetmap::tempmap_ack_t> Acks(const RecordingPublisher& out) {
  return out.Decoded<fleetmap::tempmap_ack_t>(lcmtypes::kTempMapAckChannel);
}

// A 1 MB tmpfs as the state folder, in a mount namespace of this test's own (gtest runs every
// test in a process of its own under ctest), so nothing stays mounted if the test dies.
TEST(AggregatorFaultTest, ADiskFullWhileMergingAcknowledgesNothingSaysSoAndRecovers) {
  fleetmap::testing::ScratchFolder folder;
  if (::unshare(CLONE_NEWNS) != 0 ||
      ::mount(nullptr, "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0 ||
      ::mount("tmpfs", folder.path().c_str(), "tmpfs", 0, "size=1m,mode=0700") != 0) {
    GTEST_SKIP() << "cannot mount a tmpfs (needs root and mount namespaces): "
                 << std::strerror(errno);
  }
  const std::string state = folder.path() + "/state";
  std::filesystem::create_directories(state);
  RecordingPublisher out;
  LogLines log;
  AggregatorNodeOptions options;
  options.limits.merges_per_min = 1e6;  // merges as fast as the test sends them
  auto node = MakeNode(&out, log.Sink(), state, options);
  // The disk fills. The journal's last page (4 KB) still holds a few dozen merge records of
  // ~100 bytes: maps go on merging until one does not fit.
  const std::string filler = FillDisk(folder.path());
  std::vector<std::vector<uint8_t>> failed;
  size_t acks_before = 0;
  for (int i = 0; i < 100 && failed.empty(); ++i) {
    const auto tiles = TileMessages(testing::PalletMap(i), kUtime + 20'000'000LL * i);
    acks_before = Acks(out).size();
    Feed(*node, "v1", tiles, 1.0 + i);
    if (node->counters().persist_errors > 0) failed = tiles;
  }
  ASSERT_FALSE(failed.empty()) << "the journal never filled the disk";
  const uint64_t version = node->aggregator().store().version();
  node->Tick(20.0);
  EXPECT_EQ(Acks(out).size(), acks_before) << "nothing acknowledged: the journal write failed";
  EXPECT_EQ(node->state(), "persist_failed");
  EXPECT_EQ(log.Containing("not journaled, not acknowledged"), 1);
  const auto status = out.Decoded<fleetmap::status_t>("STATUS_aggregator");
  ASSERT_FALSE(status.empty());
  EXPECT_EQ(status.back().state, "persist_failed");
  Feed(*node, "v1", {failed.back()}, 21.0);  // a resend while the disk is still full
  EXPECT_EQ(Acks(out).size(), acks_before);
  EXPECT_GE(node->counters().persist_errors, 2);  // tried again at the tick and the resend
  EXPECT_EQ(node->aggregator().store().version(), version);

  std::filesystem::remove(filler);  // space returns
  Feed(*node, "v1", {failed.back()}, 22.0);
  ASSERT_EQ(Acks(out).size(), acks_before + 1);
  EXPECT_NE(Acks(out).back().outcome, fleetmap::tempmap_ack_t::PENDING);
  EXPECT_EQ(node->state(), "running");
  const uint64_t final_version = node->aggregator().store().version();
  std::printf("disk full: %zu maps answered before the journal filled the disk\n", acks_before);

  // Nothing acknowledged was lost: a restarted aggregator holds both merges.
  const std::string hash = node->FinalLine();
  node.reset();
  auto again = MakeNode(&out, {}, state);
  EXPECT_EQ(again->aggregator().store().version(), final_version);
  const auto map_part = [](const std::string& line) {
    return line.substr(0, line.find(" merged"));
  };
  EXPECT_EQ(map_part(again->FinalLine()), map_part(hash));
}

// A vehicle's clock jumps a year ahead, then a year back, then returns: every map is still
// answered (merged, or rejected with its reason), nothing crashes, and a map whose time went
// back is not taken as older evidence than it is.
TEST(AggregatorFaultTest, AVehicleClockJumpingAheadAndBackStillGetsEveryMapAnswered) {
  RecordingPublisher out;
  auto node = MakeNode(&out);
  constexpr int64_t kYear = 365LL * 24 * 3600 * 1'000'000;
  const std::vector<int64_t> jumps = {0, kYear, -kYear, 0};
  for (size_t i = 0; i < jumps.size(); ++i) {
    core::TempMap map = PalletMaps()[i];
    const double shift_s = static_cast<double>(jumps[i]) * 1e-6;
    map.start_s += shift_s;
    map.end_s += shift_s;
    for (auto& p : map.trajectory_in_temp) p.stamp_s += shift_s;
    Feed(*node, "v1", TileMessages(map, kUtime + jumps[i] + 20'000'000 * int64_t(i)),
         1.0 + static_cast<double>(i));
  }
  const auto acks = Acks(out);
  ASSERT_EQ(acks.size(), jumps.size());
  for (const auto& a : acks) {
    EXPECT_TRUE(a.outcome == fleetmap::tempmap_ack_t::MERGED ||
                (a.outcome == fleetmap::tempmap_ack_t::REJECTED && !a.reason.empty()))
        << int(a.outcome) << " " << a.reason;
  }
  EXPECT_EQ(node->counters().maps_merged + node->counters().maps_rejected, 4);
  EXPECT_GE(node->counters().maps_merged, 1);
  const auto reports = out.Decoded<fleetmap::merge_report_t>(lcmtypes::kMergeReportChannel);
  ASSERT_EQ(reports.size(), jumps.size());
  for (size_t i = 0; i < reports.size(); ++i)
    std::printf("clock jump %+.0f s: %s %s\n", static_cast<double>(jumps[i]) * 1e-6,
                reports[i].accepted ? "merged" : "rejected", reports[i].reason.c_str());
}

}  // namespace
}  // namespace fleetmap::aggregator::node
