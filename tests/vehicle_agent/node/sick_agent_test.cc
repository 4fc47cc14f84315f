// End to end through the real SICK driver: the scanner emulator serves the simulated room's
// scans over TCP on loopback, the agent's SickScanInput (drivers/sick's client) receives them,
// the node localizes with the simulator's odometry; the scanner is cut and restarted, and the
// agent reconnects and carries on.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

#include "sim/sick/scan_source.h"
#include "sim/sick/scanner_emulator.h"
#include "tests/vehicle_agent/node/node_test_util.h"
#include "tests/vehicle_agent/node/tcp_cut_proxy.h"
#include "vehicle_agent/node/agent_config.h"
#include "vehicle_agent/node/sick_scan_input.h"

namespace fleetmap::vehicle_agent::node {
namespace {

using testing::RecordingPublisher;

// The emulator's scanner, `skip` scans into the run (a restarted scanner goes on in time).
std::unique_ptr<sim::sick::ScannerEmulator> StartScanner(const sim::World& world, int port,
                                                         uint64_t skip) {
  auto source = sim::sick::SimulatorScanSource::Create(world, 0);
  EXPECT_TRUE(source.ok()) << source.status().ToString();
  for (uint64_t i = 0; i < skip; ++i) (*source)->Next();
  sim::sick::EmulatorOptions o;
  o.port = port;
  o.protocol = drivers::sick::ColaProtocol::kColaB;
  o.require_login = true;
  o.spin_up_s = 0.2;
  auto emulator = std::make_unique<sim::sick::ScannerEmulator>(o, std::move(source).value());
  const core::Status started = emulator->Start();
  EXPECT_TRUE(started.ok()) << started.ToString();
  return emulator;
}

// Feeds the node: each scan from the driver with the simulator's odometry up to the scan's
// time. The scanner's device clock is the simulation's clock, so a scan's host stamp minus
// its device stamp maps simulated time to the host time the driver stamps in.
class Feeder {
 public:
  Feeder(const sim::World& world, AgentNode* node)
      : world_(world), odometry_(&world), node_(node) {}

  void Scan(const DriverScan& scan) {
    const double offset = scan.scan.stamp_s - scan.device_stamp_s;
    while (true) {
      if (!pending_) pending_ = odometry_.Next();
      if (!pending_ || sim::EventTime(*pending_) > scan.device_stamp_s) break;
      if (const auto* o = std::get_if<sim::OdometryEvent>(&*pending_))
        node_->OnDriverOdometry({o->stamp_s + offset, o->odom_pose, o->v_mps, o->omega_radps});
      pending_.reset();
    }
    truth_[lcmtypes::ToUtime(scan.scan.stamp_s)] =
        world_.VehicleStateAt(0, scan.device_stamp_s).pose;
    node_->OnDriverScan(scan.scan);
    node_->Tick(scan.scan.stamp_s);
  }
  // Position error of every POSE_ the node sent, in order.
  std::vector<double> Errors(const RecordingPublisher& out) const {
    std::vector<double> errors;
    for (const auto& p : out.Decoded<fleetmap::pose_with_covariance_t>("POSE_v1")) {
      const core::Pose2& t = truth_.at(p.utime);
      errors.push_back(std::hypot(p.pose.x_m - t.x_m, p.pose.y_m - t.y_m));
    }
    return errors;
  }

 private:
  const sim::World& world_;
  sim::Simulator odometry_;
  std::optional<sim::SimEvent> pending_;
  AgentNode* node_;
  std::map<int64_t, core::Pose2> truth_;
};

double Median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// The emulator's scanner on loopback, with short timeouts and backoff.
SickInputOptions QuickInput(int port) {
  SickInputOptions o;
  o.client.host = "127.0.0.1";
  o.client.port = port;
  o.client.protocol = drivers::sick::ColaProtocol::kColaB;
  o.client.connect_timeout_s = 0.5;
  o.client.silence_timeout_s = 0.5;
  o.client.reconnect_backoff_initial_s = 0.05;
  o.client.reconnect_backoff_max_s = 0.2;
  EXPECT_TRUE(o.Validate().ok());
  return o;
}

// Scans until `count` arrived; fails the test after a generous deadline (not a timing check).
int Receive(SickScanInput& input, Feeder& feeder, int count) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  int got = 0;
  while (got < count && std::chrono::steady_clock::now() < deadline) {
    if (std::optional<DriverScan> scan = input.Next(0.05)) {
      feeder.Scan(*scan);
      ++got;
    }
  }
  EXPECT_EQ(got, count) << "the scanner stopped sending";
  return got;
}

TEST(SickAgentTest, LocalizesFromAScannerOverTcpAndCarriesOnAfterTheScannerRestarts) {
  const sim::World world = testing::RoomWorld("[]", 30.0);
  auto scanner = StartScanner(world, 0, 0);
  const int port = scanner->port();

  AgentNodeOptions options = testing::RoomOptions(world);
  options.scans_from_lcm = false;
  options.odometry_from_lcm = false;
  RecordingPublisher out;
  auto node = AgentNode::Create(options, &out, nullptr, world.static_map(), 0.0).value();
  for (const Subscription& s : node->Subscriptions()) EXPECT_EQ(s.link, Link::kDownlink);

  std::vector<std::string> log;
  SickScanInput input(QuickInput(port),
                      [&](LogLevel, const std::string& line) { log.push_back(line); });
  Feeder feeder(world, node.get());

  Receive(input, feeder, 75);  // 3 s
  const uint64_t sent = scanner->stats().scans_sent.load();
  scanner->Stop();  // the scanner goes away ...
  scanner.reset();
  for (int i = 0; i < 10; ++i) EXPECT_FALSE(input.Next(0.02).has_value());
  scanner = StartScanner(world, port, sent);  // ... and comes back where it was
  Receive(input, feeder, 75);
  node->SetInputCounters(input.Counters());

  const std::vector<double> errors = feeder.Errors(out);
  ASSERT_EQ(errors.size(), 150u);
  EXPECT_LT(Median(std::vector<double>(errors.begin() + 25, errors.end())), 0.03);
  EXPECT_LT(*std::max_element(errors.begin() + 75, errors.end()), 0.1);  // after reconnecting
  EXPECT_GE(testing::Counter(*node, "scanner_reconnects"), 1);
  EXPECT_EQ(testing::Counter(*node, "scanner_bad_scans"), 0);
  EXPECT_EQ(testing::Counter(*node, "scans"), 150);
  EXPECT_EQ(node->state(), "running");
  // The connection's loss and return were logged once each.
  ASSERT_GE(log.size(), 3u);
  EXPECT_NE(log[0].find("connected"), std::string::npos);
  EXPECT_NE(log[1].find("lost"), std::string::npos);
}

// A scanner that never starts measuring (here: the agent told not to send LMCstartmeas) is
// tried again and again; the log says so once, with the reason, and STATUS counts the rest.
TEST(SickAgentTest, AScannerThatSendsNoScansIsLoggedOnceAndCounted) {
  const sim::World world = testing::RoomWorld("[]", 30.0);
  auto scanner = StartScanner(world, 0, 0);
  SickInputOptions input_options = QuickInput(scanner->port());
  input_options.client.start_measurement = false;
  input_options.client.first_scan_timeout_s = 0.2;
  std::vector<std::string> log;
  SickScanInput input(input_options,
                      [&](LogLevel, const std::string& line) { log.push_back(line); });
  int64_t silences = 0;
  for (int i = 0; i < 100 && silences < 3; ++i) {
    EXPECT_FALSE(input.Next(0.05).has_value());
    for (const auto& [name, value] : input.Counters())
      if (name == "scanner_silences") silences = value;
  }
  ASSERT_GE(silences, 3);
  ASSERT_EQ(log.size(), 2u);
  EXPECT_NE(log[0].find("connected"), std::string::npos) << log[0];
  EXPECT_NE(log[1].find("no scan within"), std::string::npos) << log[1];
}

// The TCP connection to the scanner is cut while the scanner keeps running (a
// pulled cable, a switch restart) and restored after outages of different lengths; the
// agent reconnects each time. How long after the restore the first scan arrives is printed
// as a figure (not asserted: it depends on where the backoff was), for the agent's default
// backoff (0.1 s doubling to 0.5 s) and for the driver's (doubling to 5 s).
TEST(SickAgentTest, AfterTheScannerConnectionIsCutAndRestoredTheAgentReconnects) {
  const sim::World world = testing::RoomWorld("[]", 60.0);
  for (double max_backoff_s : {AgentConfig().sick.client.reconnect_backoff_max_s, 5.0}) {
    auto scanner = StartScanner(world, 0, 0);
    testing::TcpCutProxy proxy(scanner->port());
    AgentNodeOptions options = testing::RoomOptions(world);
    options.scans_from_lcm = false;
    options.odometry_from_lcm = false;
    RecordingPublisher out;
    auto node = AgentNode::Create(options, &out, nullptr, world.static_map(), 0.0).value();
    SickInputOptions input_options = AgentConfig().sick;  // the agent's defaults
    input_options.client.host = "127.0.0.1";
    input_options.client.port = proxy.port();
    input_options.client.reconnect_backoff_max_s = max_backoff_s;
    ASSERT_TRUE(input_options.Validate().ok());
    SickScanInput input(input_options, {});
    Feeder feeder(world, node.get());
    Receive(input, feeder, 25);
    const std::vector<double> outages_s = {0.3, 1.0, 2.0};
    for (double outage_s : outages_s) {
      proxy.Cut();
      const auto cut = std::chrono::steady_clock::now();
      while (std::chrono::steady_clock::now() - cut < std::chrono::duration<double>(outage_s))
        EXPECT_FALSE(input.Next(0.02).has_value());
      proxy.Restore();
      const auto restored = std::chrono::steady_clock::now();
      std::optional<DriverScan> first;
      while (!first && std::chrono::steady_clock::now() - restored < std::chrono::seconds(30))
        first = input.Next(0.005);
      ASSERT_TRUE(first.has_value()) << "no scan after the connection was restored";
      const double took_s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - restored).count();
      std::printf("figure scanner.first_scan_after_restore_s backoff_max=%.1f outage=%.1f: %.3f\n",
                  max_backoff_s, outage_s, took_s);
      feeder.Scan(*first);
      Receive(input, feeder, 10);
    }
    node->SetInputCounters(input.Counters());
    const auto reconnects = static_cast<int64_t>(outages_s.size());
    EXPECT_EQ(testing::Counter(*node, "scanner_reconnects"), reconnects);
    EXPECT_EQ(testing::Counter(*node, "scanner_disconnects"), reconnects);
    EXPECT_EQ(testing::Counter(*node, "scanner_bad_scans"), 0);
    EXPECT_EQ(node->state(), "running");
    // Localization carried on across the gaps.
    const std::vector<double> errors = feeder.Errors(out);
    EXPECT_LT(Median(std::vector<double>(errors.begin() + 20, errors.end())), 0.05);
  }
}

}  // namespace
}  // namespace fleetmap::vehicle_agent::node
