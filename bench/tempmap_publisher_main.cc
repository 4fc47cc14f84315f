// fleetmap-bench-tempmap-publisher: N simulated vehicles, each closing a temporary map every
// PERIOD seconds, for the aggregator's scaling benchmark (bench/aggregator_scaling_bench.sh).
// The temporary maps are real ones: every complete map (all its tiles) that the agents sent in
// a recorded fleet run (an uplink LCM log of scripts/fleet_run.sh). Vehicle v of N sends its
// k-th map at v * PERIOD / N + k * PERIOD seconds, the recorded map (v + k) modulo their
// count, renamed: vehicle id `benchNNN`, sequence k + 1, times moved to now; all its tiles at
// once on TEMPMAP_<id>, once (on loopback nothing is lost, so no resends are needed).
#include <chrono>
#include <csignal>
#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "auth/trailer.h"
#include "core/command_line.h"
#include "fleetmap/tempmap_tile_t.hpp"
#include "lcmtypes/channels.h"

namespace {

volatile std::sig_atomic_t g_stop = 0;
void OnSignal(int) { g_stop = 1; }

using Map = std::vector<fleetmap::tempmap_tile_t>;  // every tile, by index

struct ReadCounts {
  int64_t tiles = 0;      // messages on a temporary map's channel
  int64_t undecoded = 0;  // of those, not a tempmap_tile_t
};

// Every complete temporary map in the log, in the order its last tile arrived. Agents append
// an authentication trailer to every message (auth/trailer.h): it is split off first.
std::vector<Map> ReadMaps(const std::string& path, ReadCounts* counts) {
  std::vector<Map> complete;
  using Key = std::pair<std::string, int32_t>;  // (vehicle, sequence)
  std::map<Key, std::map<int32_t, fleetmap::tempmap_tile_t>> partial;
  std::set<Key> taken;  // complete already: later tiles are resends
  lcm::LogFile log(path, "r");
  if (!log.good()) return complete;
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    if (!fleetmap::lcmtypes::IsTempMapTileChannel(e->channel)) continue;
    ++counts->tiles;
    const auto size = static_cast<int>(fleetmap::auth::PayloadSize(e->data, e->datalen));
    fleetmap::tempmap_tile_t t;
    if (t.decode(e->data, 0, size) != size || t.tile_count <= 0 || t.tile_index < 0 ||
        t.tile_index >= t.tile_count) {
      ++counts->undecoded;
      continue;
    }
    const Key key{t.vehicle_id, t.tempmap_seq};
    if (taken.count(key) != 0) continue;
    auto& tiles = partial[key];
    tiles.emplace(t.tile_index, t);
    if (static_cast<int32_t>(tiles.size()) < t.tile_count) continue;
    Map map;
    for (auto& [index, tile] : tiles) map.push_back(tile);
    complete.push_back(std::move(map));
    partial.erase(key);
    taken.insert(key);
  }
  return complete;
}

int64_t NowUtime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app(
      "N simulated vehicles, each closing a temporary map every PERIOD seconds: the complete\n"
      "temporary maps of a recorded uplink log, renamed, sent on TEMPMAP_benchNNN.\n"
      "Prints one line at the end: maps and tiles sent.",
      "fleetmap-bench-tempmap-publisher");
  fleetmap::core::AddVersionFlag(app);
  std::string log_path, url;
  int vehicles = 10;
  double period_s = 10, duration_s = 60;
  app.add_option("--log", log_path, "the uplink LCM log of a fleet run")->required();
  app.add_option("--url", url, "the LCM URL to send on")->required();
  app.add_option("--vehicles", vehicles, "simulated vehicles")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  app.add_option("--period", period_s, "each vehicle closes a map every this many seconds")
      ->check(fleetmap::core::Positive())
      ->capture_default_str();
  app.add_option("--duration", duration_s, "stop after this many seconds")
      ->check(fleetmap::core::Positive())
      ->capture_default_str();
  if (const auto exit_status = fleetmap::core::ParseCommandLine(app, argc, argv))
    return *exit_status;
  ReadCounts counts;
  const std::vector<Map> maps = ReadMaps(log_path, &counts);
  if (maps.empty())
    return std::fprintf(stderr,
                        "tempmap-publisher: %s: no complete temporary map (%lld tile messages, "
                        "%lld of them not a tempmap_tile_t)\n",
                        log_path.c_str(), static_cast<long long>(counts.tiles),
                        static_cast<long long>(counts.undecoded)),
           1;
  lcm::LCM lcm(url);
  if (!lcm.good()) return std::fprintf(stderr, "tempmap-publisher: %s: no LCM\n", url.c_str()), 1;
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  size_t tiles_in_maps = 0;
  for (const Map& m : maps) tiles_in_maps += m.size();
  std::fprintf(stderr, "tempmap-publisher: %zu recorded maps (%.1f tiles each), %d vehicles\n",
               maps.size(), double(tiles_in_maps) / maps.size(), vehicles);

  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  // (due time in s from start, vehicle), earliest first.
  std::multimap<double, int> due;
  for (int v = 0; v < vehicles; ++v) due.emplace(v * period_s / vehicles, v);
  std::vector<int> sent(vehicles, 0);
  int64_t maps_sent = 0, tiles_sent = 0;
  while (!g_stop) {
    const auto [at_s, v] = *due.begin();
    if (at_s >= duration_s) break;
    std::this_thread::sleep_until(
        start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(at_s)));
    if (g_stop) break;
    due.erase(due.begin());
    const Map& map = maps[(v + sent[v]) % maps.size()];
    char id[16];
    std::snprintf(id, sizeof id, "bench%03d", v);
    const int64_t now = NowUtime();
    for (fleetmap::tempmap_tile_t tile : map) {
      tile.vehicle_id = id;
      tile.tempmap_seq = sent[v] + 1;
      tile.start_utime = now - (tile.end_utime - tile.start_utime);
      tile.end_utime = now;
      tile.utime = now;
      lcm.publish(fleetmap::lcmtypes::TempMapChannel(id), &tile);
      ++tiles_sent;
    }
    ++sent[v];
    ++maps_sent;
    due.emplace(at_s + period_s, v);
  }
  std::printf("tempmap-publisher: %lld maps, %lld tiles sent\n", static_cast<long long>(maps_sent),
              static_cast<long long>(tiles_sent));
  return 0;
}
