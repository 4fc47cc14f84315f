// fleetmap-record: a burst far beyond LCM's default 30-message queue is recorded whole and in
// order, the channel filter holds, a write error (a full disk) is an error and not a short log,
// and an existing log is not overwritten by accident.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/multicast.h"
#include "tests/support/process.h"

namespace {

namespace fs = std::filesystem;
using fleetmap::testing::Process;
using fleetmap::testing::ReadText;
using fleetmap::testing::RunToExit;

// Each test its own group and port: ctest runs the tests of this file in parallel, and on
// Linux a socket bound to a port receives every group joined on that port.
const std::string kBurstUrl = "udpm://239.255.78.1:7831?ttl=0&recv_buf_size=8388608";
const std::string kFullDiskUrl = "udpm://239.255.78.2:7832?ttl=0&recv_buf_size=8388608";
const std::string kKeepUrl = "udpm://239.255.78.3:7833?ttl=0";

class RecordTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("fleetmap_record_test_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::unique_ptr<Process> StartRecorder(const std::string& url,
                                         const std::vector<std::string>& extra) {
    std::vector<std::string> args = {FLEETMAP_RECORD_BINARY, "--lcm-url", url, "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    auto recorder = std::make_unique<Process>(args, dir_ / "out.txt", dir_ / "err.txt");
    // Give it time to join the group; messages sent before that are not this test's concern.
    std::this_thread::sleep_for(std::chrono::milliseconds(700));
    return recorder;
  }
  static int Stop(Process& recorder) {
    recorder.Signal(SIGTERM);
    return recorder.Wait(30);
  }

  fs::path dir_;
};

// Message i carries i in its first 4 bytes and 196 more bytes of i's low byte.
std::vector<uint8_t> Payload(uint32_t i) {
  std::vector<uint8_t> p(200, static_cast<uint8_t>(i));
  std::memcpy(p.data(), &i, sizeof i);
  return p;
}

TEST_F(RecordTest, BurstBeyondLcmDefaultQueueIsRecordedWholeAndInOrder) {
  FLEETMAP_REQUIRE_MULTICAST(kBurstUrl);
  const std::string log = dir_ / "burst.lcmlog";
  auto recorder = StartRecorder(kBurstUrl, {"--channel", "TEMPMAP_.*", log});
  ASSERT_TRUE(recorder->started());
  lcm::LCM lcm(kBurstUrl);
  ASSERT_TRUE(lcm.good());
  // 3000 x 200 B fits the 8 MB receive buffer, so the kernel drops nothing; LCM's default
  // queue of 30 would (lcm-logger kept about 250 of such a burst on a 2-core x86_64 virtual
  // machine).
  constexpr uint32_t kCount = 3000;
  for (uint32_t i = 0; i < kCount; ++i) {
    const std::vector<uint8_t> p = Payload(i);
    ASSERT_EQ(lcm.publish("TEMPMAP_V1", p.data(), static_cast<unsigned>(p.size())), 0);
    if (i % 500 == 0) {
      const uint8_t other = 1;
      lcm.publish("POSE_V1", &other, 1);  // not matched by --channel
    }
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  ASSERT_EQ(Stop(*recorder), 0) << ReadText(dir_ / "err.txt");
  EXPECT_NE(ReadText(dir_ / "out.txt").find("3000 messages"), std::string::npos);

  lcm::LogFile file(log, "r");
  ASSERT_TRUE(file.good());
  uint32_t next = 0;
  int64_t last_stamp = 0;
  while (const lcm::LogEvent* ev = file.readNextEvent()) {
    ASSERT_EQ(ev->channel, "TEMPMAP_V1");
    ASSERT_EQ(ev->datalen, 200);
    EXPECT_EQ(std::memcmp(ev->data, Payload(next).data(), 200), 0) << "message " << next;
    EXPECT_GE(ev->timestamp, last_stamp);
    last_stamp = ev->timestamp;
    ++next;
  }
  EXPECT_EQ(next, kCount);
}

TEST_F(RecordTest, FullDiskIsAnErrorNotAShortLog) {
  FLEETMAP_REQUIRE_MULTICAST(kFullDiskUrl);
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full here";
  auto recorder = StartRecorder(kFullDiskUrl, {"--force", "/dev/full"});
  ASSERT_TRUE(recorder->started());
  lcm::LCM lcm(kFullDiskUrl);
  const std::vector<uint8_t> p = Payload(7);
  for (int i = 0; i < 100; ++i)
    lcm.publish("TEMPMAP_V1", p.data(), static_cast<unsigned>(p.size()));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_EQ(Stop(*recorder), 1);
  EXPECT_NE(ReadText(dir_ / "err.txt").find("failed"), std::string::npos)
      << ReadText(dir_ / "err.txt");
}

TEST_F(RecordTest, KeepsAnExistingLogUnlessForced) {
  const std::string log = dir_ / "kept.lcmlog";
  { std::ofstream(log) << "earlier run"; }
  EXPECT_EQ(RunToExit({FLEETMAP_RECORD_BINARY, "--lcm-url", kKeepUrl, log}, dir_ / "out.txt",
                      dir_ / "err.txt", 30),
            2);
  EXPECT_EQ(ReadText(log), "earlier run");
  EXPECT_NE(ReadText(dir_ / "err.txt").find("--force"), std::string::npos);
}

TEST_F(RecordTest, HelpAndUsageErrors) {
  EXPECT_EQ(RunToExit({FLEETMAP_RECORD_BINARY, "--help"}, dir_ / "o1", dir_ / "e1", 30), 0);
  EXPECT_NE(ReadText(dir_ / "o1").find("Usage: fleetmap-record"), std::string::npos);
  EXPECT_EQ(RunToExit({FLEETMAP_RECORD_BINARY}, dir_ / "o2", dir_ / "e2", 30), 2);
  EXPECT_EQ(RunToExit({FLEETMAP_RECORD_BINARY, "--queue", "0", "x"}, dir_ / "o3", dir_ / "e3", 30),
            2);
}

}  // namespace
