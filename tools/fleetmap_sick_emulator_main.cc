// fleetmap-sick-emulator: a SICK scanner on a TCP port (CoLa-A or CoLa-B), fed by the
// simulator or by replaying a recording, so the driver runs end to end without hardware.
// With --s300-out it writes S300 continuous-output telegrams to a file or serial device.
#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>
#include <type_traits>

#include "core/number_text.h"
#include "core/version.h"
#include "tools/sickemu/s300_output.h"
#include "tools/sickemu/scan_source.h"
#include "tools/sickemu/scanner_emulator.h"

namespace {

std::atomic<bool> g_stop{false};  // set by SIGINT/SIGTERM: the process edge only

constexpr const char* kUsage =
    R"(usage: fleetmap-sick-emulator (--scenario S.yaml [--vehicle N] | --replay FILE [--loop])
       [--port 2112] [--bind 127.0.0.1] [--protocol cola-b|cola-a] [--speed 1.0]
       [--require-login] [--spin-up 1.0] [--measuring] [--s300-out PATH [--count N]]
  --scenario   scans of vehicle N (default 0) of a simulated scenario
  --replay     scans of a recording: .pcapng, .pcapng.json or pysicktim .dat
  --spin-up    seconds from sMN LMCstartmeas to the first scan, as a real device spins up
  --measuring  measure from the start (no LMCstartmeas needed; Run still ends a login)
  --s300-out   instead of TCP, write N (default 100) S300 telegrams to PATH (file or tty)
Like a real scanner it sends scans only after sMN LMCstartmeas (and sMN Run after a login),
and serves one client at a time (a second connection is closed at once), until
SIGINT/SIGTERM.
)";

struct Args {
  std::string scenario, replay, s300_out;
  size_t vehicle = 0, count = 100;
  bool loop = false;
  fleetmap::sickemu::EmulatorOptions emulator;
};

// False on a usage error, after saying which flag was wrong when it was a value.
bool Parse(int argc, char** argv, Args& a) {
  using fleetmap::core::ParseCount;
  using fleetmap::core::ParseNumber;
  bool values_ok = true;
  auto take = [&](const auto& parsed, auto& into) {
    if (parsed.ok()) {
      into = static_cast<std::remove_reference_t<decltype(into)>>(*parsed);
      return;
    }
    std::fprintf(stderr, "fleetmap-sick-emulator: %s\n", parsed.status().message().c_str());
    values_ok = false;
  };
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    auto value = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (k == "--scenario")
      a.scenario = value();
    else if (k == "--replay")
      a.replay = value();
    else if (k == "--vehicle")
      take(ParseCount(value(), k, 1000), a.vehicle);
    else if (k == "--loop")
      a.loop = true;
    else if (k == "--port")
      take(ParseCount(value(), k, 65535), a.emulator.port);
    else if (k == "--bind")
      a.emulator.bind_address = value();
    else if (k == "--speed")
      take(ParseNumber(value(), k), a.emulator.speed_factor);
    else if (k == "--require-login")
      a.emulator.require_login = true;
    else if (k == "--spin-up")
      take(ParseNumber(value(), k), a.emulator.spin_up_s);
    else if (k == "--measuring")
      a.emulator.measuring_at_power_up = true;
    else if (k == "--s300-out")
      a.s300_out = value();
    else if (k == "--count")
      take(ParseCount(value(), k, 100000000), a.count);
    else if (k == "--protocol") {
      auto p = fleetmap::drivers::sick::ParseColaProtocol(value());
      if (!p.ok()) return std::fprintf(stderr, "%s\n", p.status().ToString().c_str()), false;
      a.emulator.protocol = *p;
    } else {
      return false;
    }
  }
  return values_ok && a.scenario.empty() != a.replay.empty();
}

fleetmap::core::Result<std::unique_ptr<fleetmap::sickemu::ScanSource>> MakeSource(const Args& a) {
  using namespace fleetmap;
  if (!a.replay.empty()) {
    auto s = sickemu::RecordingScanSource::Load(a.replay, a.loop);
    if (!s.ok()) return s.status();
    return std::unique_ptr<sickemu::ScanSource>(std::move(s).value());
  }
  core::Result<sim::World> world = sim::World::Load(a.scenario);
  if (!world.ok()) return world.status();
  auto s = sickemu::SimulatorScanSource::Create(std::move(world).value(), a.vehicle);
  if (!s.ok()) return s.status();
  return std::unique_ptr<sickemu::ScanSource>(std::move(s).value());
}

int WriteS300(const Args& a, fleetmap::sickemu::ScanSource& source) {
  const int fd = open(a.s300_out.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOCTTY, 0644);
  if (fd < 0) return std::fprintf(stderr, "%s: %s\n", a.s300_out.c_str(), std::strerror(errno)), 1;
  auto n = fleetmap::sickemu::WriteS300Stream(source, fd, a.count);
  close(fd);
  if (!n.ok()) return std::fprintf(stderr, "%s\n", n.status().ToString().c_str()), 1;
  std::printf("wrote %zu S300 telegrams to %s\n", *n, a.s300_out.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (fleetmap::core::PrintVersionIfAsked(argc, argv, "fleetmap-sick-emulator")) return 0;
  if (argc > 1 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h"))
    return std::fputs(kUsage, stdout), 0;
  Args args;
  bool ok = false;
  try {
    ok = Parse(argc, argv, args);
  } catch (const std::exception&) {
    ok = false;  // a number that does not parse
  }
  if (!ok) return std::fputs(kUsage, stderr), 2;
  auto source = MakeSource(args);
  if (!source.ok()) return std::fprintf(stderr, "%s\n", source.status().ToString().c_str()), 1;
  if (!args.s300_out.empty()) return WriteS300(args, **source);
  fleetmap::sickemu::ScannerEmulator emulator(args.emulator, std::move(source).value());
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
