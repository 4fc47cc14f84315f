// End to end on loopback: the real driver (ScannerClient over TCP) against our scanner
// emulator, fed by the simulator or by a real recording, with the faults of real networks.
#include <gtest/gtest.h>

#include <thread>

#include "drivers/sick/scan_telegram_codec.h"
#include "drivers/sick/scanner_client.h"
#include "sim/sick/scan_source.h"
#include "sim/sick/scanner_emulator.h"
#include "sim/world.h"
#include "tests/support/data_dir.h"

namespace fleetmap::drivers::sick {
namespace {

std::unique_ptr<sim::sick::ScanSource> SimulatorSource() {
  const std::string dir = std::string(FLEETMAP_SOURCE_DIR) + "/sim/worlds/livinglab/";
  core::Result<sim::World> world = sim::World::Load(dir + "addition.yaml");
  EXPECT_TRUE(world.ok()) << world.status().ToString();
  return std::move(sim::sick::SimulatorScanSource::Create(std::move(world).value(), 0)).value();
}

ScannerClientOptions ClientFor(const sim::sick::ScannerEmulator& emulator, ColaProtocol protocol) {
  ScannerClientOptions o;
  o.host = "127.0.0.1";
  o.port = emulator.port();
  o.protocol = protocol;
  o.silence_timeout_s = 0.5;
  o.reconnect_backoff_initial_s = 0.05;
  o.reconnect_backoff_max_s = 0.4;
  return o;
}

sim::sick::EmulatorOptions EmulatorFor(ColaProtocol protocol) {
  sim::sick::EmulatorOptions o;
  o.port = 0;
  o.protocol = protocol;
  o.require_login = true;
  o.speed_factor = 4.0;
  o.spin_up_s = 0.6;  // longer than the client's silence timeout
  return o;
}

class EmulatorClientTest : public ::testing::TestWithParam<ColaProtocol> {};

TEST_P(EmulatorClientTest, StreamsSimulatedScansThroughTheRealDriver) {
  sim::sick::ScannerEmulator emulator(EmulatorFor(GetParam()), SimulatorSource());
  ASSERT_TRUE(emulator.Start().ok());
  ScannerClient client(ClientFor(emulator, GetParam()));
  uint16_t last_counter = 0;
  for (int i = 0; i < 20; ++i) {
    core::Result<ReceivedScan> scan = client.NextScan(5.0);
    ASSERT_TRUE(scan.ok()) << scan.status().ToString();
    // The simulator's S300: 541 beams over 270 degrees at 25 Hz, in order.
    EXPECT_EQ(scan->telegram.FindChannel("DIST1")->values.size(), 541u);
    EXPECT_EQ(scan->telegram.scan_frequency_hz(), 25.0);
    EXPECT_GT(scan->telegram.scan_counter, last_counter);
    last_counter = scan->telegram.scan_counter;
  }
  const ScannerClientStats s = client.stats();
  EXPECT_EQ(s.connects, 1u);
  EXPECT_EQ(s.silences, 0u);  // the spin-up is waited for with the first-scan timeout
  EXPECT_EQ(s.framing.bad_checksums, 0u);
  EXPECT_EQ(s.device_state, DeviceState::kBusy);  // asked while it spun up
  EXPECT_EQ(emulator.stats().logins.load(), 1u);
  EXPECT_EQ(emulator.stats().start_requests.load(), 1u);
  EXPECT_EQ(emulator.stats().run_requests.load(), 1u);
}

TEST_P(EmulatorClientTest, TheDeviceSendsNothingWithoutItsStartSequence) {
  sim::sick::ScannerEmulator emulator(EmulatorFor(GetParam()), SimulatorSource());
  ASSERT_TRUE(emulator.Start().ok());
  ScannerClientOptions o = ClientFor(emulator, GetParam());
  o.start_measurement = false;  // login and subscribe only
  o.first_scan_timeout_s = 1.0;
  ScannerClient client(o);
  EXPECT_FALSE(client.NextScan(1.5).ok());
  EXPECT_EQ(emulator.stats().scans_sent.load(), 0u);
  EXPECT_GE(client.stats().silences, 1u);
  EXPECT_NE(client.last_error().message().find("of connecting"), std::string::npos)
      << client.last_error().ToString();
}

TEST_P(EmulatorClientTest, AFirstScanTimeoutShorterThanTheSpinUpReconnectsAndSaysWhy) {
  sim::sick::ScannerEmulator emulator(EmulatorFor(GetParam()), SimulatorSource());
  ASSERT_TRUE(emulator.Start().ok());
  ScannerClientOptions o = ClientFor(emulator, GetParam());
  o.first_scan_timeout_s = 0.25;
  ScannerClient client(o);
  EXPECT_FALSE(client.NextScan(0.3).ok());
  EXPECT_NE(client.last_error().message().find("device state busy"), std::string::npos)
      << client.last_error().ToString();
  // The device goes on spinning up across connections and measures on the next one.
  ASSERT_TRUE(client.NextScan(5.0).ok());
  EXPECT_GE(client.stats().silences, 1u);
  EXPECT_GE(client.stats().connects, 2u);
  EXPECT_GE(emulator.stats().start_requests.load(), 2u);  // the sequence again on reconnect
}

TEST_P(EmulatorClientTest, SurvivesSplitWritesGarbageCorruptionAndSilence) {
  sim::sick::EmulatorOptions faults = EmulatorFor(GetParam());
  faults.max_write_bytes = 700;    // every telegram arrives in pieces
  faults.garbage_every = 3;        // garbage before every third scan
  faults.corrupt_every = 5;        // every fifth scan damaged
  faults.silent_after_scans = 12;  // then the scanner stops sending on the first connection
  sim::sick::ScannerEmulator emulator(faults, SimulatorSource());
  ASSERT_TRUE(emulator.Start().ok());
  ScannerClient client(ClientFor(emulator, GetParam()));
  int received = 0;
  while (received < 25) {
    core::Result<ReceivedScan> scan = client.NextScan(5.0);
    ASSERT_TRUE(scan.ok()) << scan.status().ToString();
    EXPECT_EQ(scan->telegram.FindChannel("DIST1")->values.size(), 541u);
    ++received;
  }
  const ScannerClientStats s = client.stats();
  EXPECT_GE(s.silences, 1u);  // the silent scanner was noticed ...
  EXPECT_GE(s.connects, 2u);  // ... and the client reconnected
  EXPECT_GT(s.framing.garbage_bytes, 0u);
  if (GetParam() == ColaProtocol::kColaB) {
    EXPECT_GE(s.framing.bad_checksums, 1u);
  }
  EXPECT_EQ(s.bad_scans, 0u);  // nothing damaged got through
}

TEST_P(EmulatorClientTest, PollingWithSrnGetsOneScanPerRequest) {
  sim::sick::ScannerEmulator emulator(EmulatorFor(GetParam()), SimulatorSource());
  ASSERT_TRUE(emulator.Start().ok());
  ScannerClientOptions o = ClientFor(emulator, GetParam());
  o.streaming = false;
  ScannerClient client(o);
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(client.NextScan(5.0).ok());
  EXPECT_EQ(emulator.stats().scans_sent.load(), 3u);
}

TEST_P(EmulatorClientTest, ASecondClientIsRefusedWhileOneIsServed) {
  sim::sick::ScannerEmulator emulator(EmulatorFor(GetParam()), SimulatorSource());
  ASSERT_TRUE(emulator.Start().ok());
  ScannerClient client(ClientFor(emulator, GetParam()));
  ASSERT_TRUE(client.NextScan(5.0).ok());
  core::Result<TcpConnection> second = TcpConnection::Connect("127.0.0.1", emulator.port(), 1.0);
  ASSERT_TRUE(second.ok()) << second.status().ToString();  // accepted by the kernel ...
  uint8_t byte = 0;
  core::Result<size_t> read = second->Read(&byte, 1, 2.0);
  EXPECT_FALSE(read.ok());  // ... and closed by the device
  EXPECT_EQ(emulator.stats().refused_connections.load(), 1u);
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(client.NextScan(5.0).ok());
  EXPECT_EQ(client.stats().connects, 1u);
}

INSTANTIATE_TEST_SUITE_P(BothProtocols, EmulatorClientTest,
                         ::testing::Values(ColaProtocol::kColaA, ColaProtocol::kColaB));

TEST(EmulatorClientTest, ReplaysARealRecordingUnchanged) {
  FLEETMAP_SKIP_WITHOUT_DATA("sick/sick_scan_xd/20210302_lms111.pcapng.json");
  const std::string path = testing::DataPath("sick/sick_scan_xd/20210302_lms111.pcapng.json");
  auto source = sim::sick::RecordingScanSource::Load(path, /*loop=*/false);
  ASSERT_TRUE(source.ok()) << source.status().ToString();
  auto recorded = sim::sick::RecordingScanSource::Load(path, false);
  sim::sick::EmulatorOptions o = EmulatorFor(ColaProtocol::kColaB);
  o.speed_factor = 10.0;
  sim::sick::ScannerEmulator emulator(o, std::move(source).value());
  ASSERT_TRUE(emulator.Start().ok());
  ScannerClient client(ClientFor(emulator, ColaProtocol::kColaB));
  for (int i = 0; i < 30; ++i) {
    core::Result<ReceivedScan> scan = client.NextScan(5.0);
    ASSERT_TRUE(scan.ok()) << scan.status().ToString();
    const ScanTelegram expected = *(*recorded)->Next();
    EXPECT_EQ(scan->telegram.FindChannel("DIST1")->values, expected.FindChannel("DIST1")->values);
    EXPECT_EQ(scan->telegram.scan_counter, expected.scan_counter);
  }
}

// SICK's own emulator on its CoLa-A port answers in ASCII but streams binary scans: bytes keep
// coming and none forms a scan. That is silence too.
TEST(EmulatorClientTest, BytesThatFormNoScanAreSilence) {
  sim::sick::EmulatorOptions e = EmulatorFor(ColaProtocol::kColaA);
  e.cola_b_scans = true;
  e.spin_up_s = 0.0;
  sim::sick::ScannerEmulator emulator(e, SimulatorSource());
  ASSERT_TRUE(emulator.Start().ok());
  ScannerClientOptions o = ClientFor(emulator, ColaProtocol::kColaA);
  o.first_scan_timeout_s = 0.5;
  ScannerClient client(o);
  EXPECT_FALSE(client.NextScan(1.5).ok());
  EXPECT_GT(emulator.stats().scans_sent.load(), 5u);
  const ScannerClientStats s = client.stats();
  EXPECT_EQ(s.scans, 0u);
  EXPECT_GE(s.silences, 1u);
  EXPECT_GE(s.connects, 2u);
  EXPECT_GT(s.framing.garbage_bytes, 1000u);
  EXPECT_NE(client.last_error().message().find("formed no telegram"), std::string::npos)
      << client.last_error().ToString();
}

TEST(EmulatorClientTest, ReconnectsWithBackoffWhenTheScannerDisappears) {
  ScannerClientOptions o;
  o.host = "127.0.0.1";
  o.port = 1;  // nothing listens there
  o.connect_timeout_s = 0.2;
  o.reconnect_backoff_initial_s = 0.02;
  o.reconnect_backoff_max_s = 0.1;
  ScannerClient client(o);
  core::Result<ReceivedScan> scan = client.NextScan(0.5);
  ASSERT_FALSE(scan.ok());
  EXPECT_NE(scan.status().message().find("connect"), std::string::npos) << scan.status().ToString();
  EXPECT_GE(client.stats().connect_failures, 3u);   // retried, with growing waits ...
  EXPECT_LE(client.stats().connect_failures, 12u);  // ... not in a busy loop
}

TEST(EmulatorClientTest, WrongPasswordIsRefusedAndReported) {
  sim::sick::ScannerEmulator emulator(EmulatorFor(ColaProtocol::kColaB), SimulatorSource());
  ASSERT_TRUE(emulator.Start().ok());
  ScannerClientOptions o = ClientFor(emulator, ColaProtocol::kColaB);
  o.login = false;  // the emulator requires a login: sEN is refused with sFA
  ScannerClient client(o);
  EXPECT_FALSE(client.NextScan(0.4).ok());
  EXPECT_GE(client.stats().error_replies, 1u);
  EXPECT_EQ(emulator.stats().scans_sent.load(), 0u);
}

}  // namespace
}  // namespace fleetmap::drivers::sick
