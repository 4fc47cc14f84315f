// SocketCAN on a real kernel: these tests need a vcan interface named by FLEETMAP_VCAN and
// can-utils (FLEETMAP_CANPLAYER, FLEETMAP_CANDUMP). ctest runs them through
// scripts/can_vm_test.sh (test can_vcan_test), on a host vcan or inside a minimal qemu VM;
// run directly without those variables they skip and say why.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/io/file_io.h"
#include "drivers/can/candump_log.h"
#include "drivers/can/diff_drive_odometry.h"
#include "drivers/can/socketcan.h"
#include "sim/can/sim_can_log.h"
#include "tests/drivers/can/can_test_world.h"

extern char** environ;

namespace fleetmap::drivers::can {
namespace {

std::string Env(const char* name) {
  const char* v = std::getenv(name);
  return v == nullptr ? "" : v;
}

#define REQUIRE_VCAN()                                                                        \
  if (Env("FLEETMAP_VCAN").empty() || Env("FLEETMAP_CANPLAYER").empty()) {                    \
    GTEST_SKIP() << "FLEETMAP_VCAN/FLEETMAP_CANPLAYER are not set: run through "              \
                    "scripts/can_vm_test.sh (ctest -R can_vcan_test), which provides a vcan"; \
  }

pid_t Spawn(const std::vector<std::string>& args, const std::string& stdout_path = "") {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (!stdout_path.empty()) {
    posix_spawn_file_actions_addopen(&actions, 1, stdout_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
  }
  pid_t pid = -1;
  const int r = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return r == 0 ? pid : -1;
}

// Exit status, or -1 while running.
int Poll(pid_t pid) {
  int status = 0;
  if (waitpid(pid, &status, WNOHANG) != pid) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

SocketCan OpenVcan(SocketCanOptions options = {}) {
  options.interface = Env("FLEETMAP_VCAN");
  core::Result<SocketCan> s = SocketCan::Open(options);
  EXPECT_TRUE(s.ok()) << s.status().ToString();
  return std::move(s).value();
}

// Reads frames until `done()` and the bus has been quiet for `quiet_s`, or `limit_s` passed.
template <typename Done>
std::vector<CanFrame> Collect(SocketCan& socket, Done done, double quiet_s, double limit_s) {
  std::vector<CanFrame> frames;
  const auto start = std::chrono::steady_clock::now();
  auto last = start;
  while (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() <
         limit_s) {
    const size_t before = frames.size();
    EXPECT_TRUE(socket.WaitReadable(0.05).ok());
    EXPECT_TRUE(socket.ReadAvailable(frames).ok());
    const auto now = std::chrono::steady_clock::now();
    if (frames.size() != before) last = now;
    if (done() && std::chrono::duration<double>(now - last).count() > quiet_s) break;
  }
  return frames;
}

TEST(VcanOdometryTest, CanplayerReplayOfTheSimulatorsLogDecodesToItsOdometry) {
  REQUIRE_VCAN();
  sim::can::SimCanLogOptions options;
  options.duration_s = 8.0;
  options.start_ticks = 2147483647LL - 20000;  // both wheels wrap around during the drive
  options.can.gear_ratio = 10.0;
  const sim::World world = sim::can::testing::LoopWorld();
  core::Result<sim::can::SimCanLog> log = sim::can::RecordOdometryAsCan(world, options);
  ASSERT_TRUE(log.ok()) << log.status().ToString();
  const std::string path = "/tmp/fleetmap_vcan_replay.log";
  ASSERT_TRUE(WriteCandumpLog(path, log->records).ok());

  SocketCanOptions socket_options;
  socket_options.filters = {{0x080, 0x7FF}, {0x180, 0x780}};  // SYNC and every TPDO1
  socket_options.receive_buffer_bytes = 8 << 20;  // the whole replay fits, however slow the VM
  SocketCan socket = OpenVcan(socket_options);
  const double wall_start =
      std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  const pid_t player = Spawn(
      {Env("FLEETMAP_CANPLAYER"), "-I", path, "-t", "-g", "1", Env("FLEETMAP_VCAN") + "=can0"});
  ASSERT_GT(player, 0);
  int player_status = -1;
  std::vector<CanFrame> frames = Collect(
      socket, [&] { return player_status >= 0 || (player_status = Poll(player)) >= 0; }, 0.5, 120);
  EXPECT_EQ(player_status, 0);
  ASSERT_EQ(frames.size(), log->records.size());
  EXPECT_EQ(socket.stats().kernel_drops, 0u);

  DiffDriveOdometry odometry(options.can);
  std::vector<core::OdometrySample> decoded;
  for (const CanFrame& f : frames) {
    if (auto sample = odometry.Decode(f)) decoded.push_back(*sample);
  }
  ASSERT_EQ(decoded.size(), log->odometry.size());
  const core::Pose2 origin = log->odometry.front().pose_in_odom;
  double max_error_m = 0.0, max_error_rad = 0.0;
  for (size_t i = 0; i < decoded.size(); ++i) {
    const core::Pose2 expected = core::Between(origin, log->odometry[i].pose_in_odom);
    const core::Pose2& got = decoded[i].pose_in_odom;
    max_error_m = std::max(max_error_m, std::hypot(got.x_m - expected.x_m, got.y_m - expected.y_m));
    max_error_rad =
        std::max(max_error_rad, std::abs(core::NormalizeAngle(got.theta_rad - expected.theta_rad)));
    // Kernel receive timestamps: increasing and taken during this replay.
    EXPECT_GE(decoded[i].stamp_s, wall_start - 1.0);
    if (i > 0) {
      EXPECT_GT(decoded[i].stamp_s, decoded[i - 1].stamp_s);
    }
  }
  EXPECT_LT(max_error_m, 0.002);
  EXPECT_LT(max_error_rad, 0.002);
  const core::Pose2 end = decoded.back().pose_in_odom;
  EXPECT_GT(std::hypot(end.x_m, end.y_m) + std::abs(end.theta_rad), 1.0);  // it really drove
  EXPECT_EQ(odometry.stats().incomplete_cycles, 0u);
  std::printf("vcan replay: %zu frames, %zu samples, max error %.2e m %.2e rad\n", frames.size(),
              decoded.size(), max_error_m, max_error_rad);
}

TEST(VcanOdometryTest, BadFramesOnTheBusAreCountedAndSkipped) {
  REQUIRE_VCAN();
  SocketCan reader = OpenVcan();
  SocketCan writer = OpenVcan();
  DiffDriveCanOptions can;
  auto frame = [](uint32_t id, uint8_t len, bool extended = false) {
    CanFrame f;
    f.id = id;
    f.len = len;
    f.extended = extended;
    return f;
  };
  const std::vector<CanFrame> sent = {frame(0x080, 0),
                                      frame(0x181, 2) /* DLC too short */,
                                      frame(0x185, 8) /* unknown node */,
                                      frame(0x181, 4),
                                      frame(0x182, 4),
                                      frame(0x701, 1) /* heartbeat */,
                                      frame(0x12345678, 8, true)};
  for (const CanFrame& f : sent) ASSERT_TRUE(writer.Write(f).ok());
  std::vector<CanFrame> frames = Collect(
      reader, [&] { return true; }, 0.3, 10);
  ASSERT_EQ(frames.size(), sent.size());
  DiffDriveOdometry odometry(can);
  int samples = 0;
  for (const CanFrame& f : frames) samples += odometry.Decode(f).has_value();
  EXPECT_EQ(samples, 1);
  EXPECT_EQ(odometry.stats().wrong_dlc, 1u);
  EXPECT_EQ(odometry.stats().unknown_nodes, 1u);
  EXPECT_EQ(odometry.stats().other_frames, 2u);
  EXPECT_TRUE(frames.back().extended);
  EXPECT_EQ(frames.back().id, 0x12345678u);
}

TEST(VcanOdometryTest, RealCandumpWritesLinesOurParserReads) {
  REQUIRE_VCAN();
  if (Env("FLEETMAP_CANDUMP").empty()) GTEST_SKIP() << "FLEETMAP_CANDUMP is not set";
  const std::string out = "/tmp/fleetmap_candump.log";
  const pid_t dump = Spawn({Env("FLEETMAP_CANDUMP"), "-L", "-n", "4", Env("FLEETMAP_VCAN")}, out);
  ASSERT_GT(dump, 0);
  usleep(300000);  // let candump bind before we send
  SocketCanOptions fd_options;
  fd_options.enable_fd = true;
  SocketCan writer = OpenVcan(fd_options);
  CanFrame a;
  a.id = 0x243;
  a.len = 8;
  for (int i = 0; i < 8; ++i) a.data[i] = static_cast<uint8_t>(0xA0 + i);
  CanFrame b;
  b.id = 0x1ABCDEF0;
  b.extended = true;
  b.len = 2;
  CanFrame c;
  c.id = 0x123;
  c.rtr = true;
  CanFrame d;
  d.id = 0x321;
  d.fd = true;
  d.fd_flags = kCanFdBitRateSwitch;
  d.len = 12;
  for (const CanFrame& f : {a, b, c, d}) ASSERT_TRUE(writer.Write(f).ok());
  int status = -1;
  for (int i = 0; i < 100 && status < 0; ++i, usleep(50000)) status = Poll(dump);
  ASSERT_EQ(status, 0);
  core::Result<CandumpLog> log = ReadCandumpLog(out);
  ASSERT_TRUE(log.ok());
  ASSERT_EQ(log->records.size(), 4u) << (log->errors.empty() ? "" : log->errors.front());
  EXPECT_EQ(log->records[0].frame.ToString(), a.ToString());
  EXPECT_EQ(log->records[1].frame.ToString(), b.ToString());
  EXPECT_EQ(log->records[2].frame.ToString(), c.ToString());
  EXPECT_EQ(log->records[3].frame.ToString(), d.ToString());
  EXPECT_EQ(log->records[0].interface, Env("FLEETMAP_VCAN"));
}

}  // namespace
}  // namespace fleetmap::drivers::can
