// fleetmap-sick-emulator: a SICK scanner on a TCP port (CoLa-A or CoLa-B), fed by the
// simulator or by replaying a recording, so the driver runs end to end without hardware.
// With --s300-out it writes S300 continuous-output telegrams to a file or serial device.
#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <thread>

#include "core/command_line.h"
#include "sim/sick/s300_output.h"
#include "sim/sick/scan_source.h"
#include "sim/sick/scanner_emulator.h"

namespace {

std::atomic<bool> g_stop{false};  // set by SIGINT/SIGTERM: the process edge only

struct Args {
  std::string scenario, replay, s300_out;
  size_t vehicle = 0, count = 100;
  bool loop = false;
  fleetmap::sim::sick::EmulatorOptions emulator;
};

// Reads the command line into `a`. No value: go on; otherwise the exit status.
std::optional<int> Parse(int argc, char** argv, Args& a) {
  CLI::App app(
      "A SICK scanner on a TCP port (CoLa-A or CoLa-B), fed by the simulator or by replaying\n"
      "a recording, so the driver runs end to end without hardware. Like a real scanner it\n"
      "sends scans only after sMN LMCstartmeas (and sMN Run after a login), and serves one\n"
      "client at a time (a second connection is closed at once), until SIGINT/SIGTERM.\n"
      "Exit status: 0 after a stop, 1 the source or the port failed, 2 usage errors.",
      "fleetmap-sick-emulator");
  fleetmap::core::AddVersionFlag(app);
  auto* scenario =
      app.add_option("--scenario", a.scenario, "scans of a vehicle of a simulated scenario");
  auto* replay = app.add_option("--replay", a.replay,
                                "scans of a recording: .pcapng, .pcapng.json or pysicktim .dat");
  scenario->excludes(replay);
  app.add_option("--vehicle", a.vehicle, "the scenario's vehicle")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  app.add_flag("--loop", a.loop, "replay the recording again and again");
  app.add_option("--port", a.emulator.port, "TCP port (0: any free port)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  app.add_option("--bind", a.emulator.bind_address, "address to listen on")->capture_default_str();
  std::string protocol = fleetmap::drivers::sick::ColaProtocolName(a.emulator.protocol);
  app.add_option("--protocol", protocol, "cola-b or cola-a")->capture_default_str();
  app.add_option("--speed", a.emulator.speed_factor, "scans this many times faster than real")
      ->check(fleetmap::core::Finite())
      ->capture_default_str();
  app.add_flag("--require-login", a.emulator.require_login, "refuse requests before a login");
  app.add_option("--spin-up", a.emulator.spin_up_s,
                 "seconds from sMN LMCstartmeas to the first scan, as a real device spins up")
      ->check(fleetmap::core::Finite())
      ->capture_default_str();
  app.add_flag("--measuring", a.emulator.measuring_at_power_up,
               "measure from the start (no LMCstartmeas needed; Run still ends a login)");
  app.add_option("--s300-out", a.s300_out,
                 "instead of TCP, write --count S300 telegrams to this file or tty");
  app.add_option("--count", a.count, "S300 telegrams to write")
      ->check(CLI::Range(0, 100000000))
      ->capture_default_str();
  if (const auto exit_status = fleetmap::core::ParseCommandLine(app, argc, argv))
    return exit_status;
  auto p = fleetmap::drivers::sick::ParseColaProtocol(protocol);
  if (!p.ok()) return std::fprintf(stderr, "%s\n", p.status().ToString().c_str()), 2;
  a.emulator.protocol = *p;
  if (a.scenario.empty() == a.replay.empty()) {
    std::fprintf(stderr, "fleetmap-sick-emulator: one of --scenario and --replay (see --help)\n");
    return 2;
  }
  return std::nullopt;
}

fleetmap::core::Result<std::unique_ptr<fleetmap::sim::sick::ScanSource>> MakeSource(const Args& a) {
  using namespace fleetmap;
  if (!a.replay.empty()) {
    auto s = sim::sick::RecordingScanSource::Load(a.replay, a.loop);
    if (!s.ok()) return s.status();
    return std::unique_ptr<sim::sick::ScanSource>(std::move(s).value());
  }
  core::Result<sim::World> world = sim::World::Load(a.scenario);
  if (!world.ok()) return world.status();
  auto s = sim::sick::SimulatorScanSource::Create(std::move(world).value(), a.vehicle);
  if (!s.ok()) return s.status();
  return std::unique_ptr<sim::sick::ScanSource>(std::move(s).value());
}

int WriteS300(const Args& a, fleetmap::sim::sick::ScanSource& source) {
  const int fd = open(a.s300_out.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOCTTY, 0644);
  if (fd < 0) return std::fprintf(stderr, "%s: %s\n", a.s300_out.c_str(), std::strerror(errno)), 1;
  auto n = fleetmap::sim::sick::WriteS300Stream(source, fd, a.count);
  close(fd);
  if (!n.ok()) return std::fprintf(stderr, "%s\n", n.status().ToString().c_str()), 1;
  std::printf("wrote %zu S300 telegrams to %s\n", *n, a.s300_out.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  if (const auto exit_status = Parse(argc, argv, args)) return *exit_status;
  auto source = MakeSource(args);
  if (!source.ok()) return std::fprintf(stderr, "%s\n", source.status().ToString().c_str()), 1;
  if (!args.s300_out.empty()) return WriteS300(args, **source);
  fleetmap::sim::sick::ScannerEmulator emulator(args.emulator, std::move(source).value());
  if (auto s = emulator.Start(); !s.ok())
    return std::fprintf(stderr, "%s\n", s.ToString().c_str()), 1;
  std::printf("fleetmap-sick-emulator: %s on %s:%d\n",
              fleetmap::drivers::sick::ColaProtocolName(args.emulator.protocol),
              args.emulator.bind_address.c_str(), emulator.port());
  std::fflush(stdout);
  std::signal(SIGINT, [](int) { g_stop = true; });
  std::signal(SIGTERM, [](int) { g_stop = true; });
  while (!g_stop) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  emulator.Stop();
  std::printf("served %llu connections, %llu scans\n",
              static_cast<unsigned long long>(emulator.stats().connections.load()),
              static_cast<unsigned long long>(emulator.stats().scans_sent.load()));
  return 0;
}
