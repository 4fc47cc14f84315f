// fleetmap-aggregator: the server of the fleet. Receives temporary maps over LCM, merges
// them into the versioned current map and sends the changes back; or replays LCM logs into
// the same code. See --help and docs/aggregator_process.md.
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "aggregator/node/aggregator_links.h"
#include "aggregator/node/aggregator_node.h"
#include "aggregator/node/log_replay.h"
#include "aggregator/node/node_config.h"
#include "aggregator/persistence/recovery_marker.h"
#include "auth/key.h"
#include "core/command_line.h"
#include "core/image/map_render.h"
#include "core/map/map_io.h"

namespace {

using namespace fleetmap;
using namespace fleetmap::aggregator::node;

constexpr char kDescription[] =
    R"(Receives temporary maps (TEMPMAP_<vehicle>) and MAP_REQUEST on the uplink, merges accepted
maps into the versioned current map and answers on the downlink: TEMPMAP_ACK, MERGE_REPORT,
MAP_DELTA, MAP_KEYFRAME, STATUS_aggregator. docs/aggregator_process.md has the details.)";

constexpr char kFooter[] =
    R"(Ends with the line "aggregator: version N map_hash HEX merged M rejected R" on stdout (the
same function in live and replay runs). SIGINT/SIGTERM: finishes the message at hand, writes
a snapshot and the final map, prints that line and exits 0.
Exit status: 0 done, 1 bad map/config/state or LCM failure, 2 usage.
Multicast on one host needs a route: run scripts/setup_multicast.sh as root.)";

volatile std::sig_atomic_t g_stop = 0;
void OnSignal(int) { g_stop = 1; }

struct Args {
  std::string map, config, state_dir, uplink_url, downlink_url, final_map, key_file;
  double duration_s = -1.0;  // below 0: until a signal
  std::vector<std::string> replay;
  bool quiet = false;
};

void DefineFlags(CLI::App& app, Args& a) {
  app.description(kDescription);
  app.footer(kFooter);
  core::AddVersionFlag(app);
  app.add_option("--map", a.map, "static map, map_server YAML + image")
      ->required()
      ->type_name("FILE");
  app.add_option("--config", a.config,
                 "YAML settings (docs/aggregator_process.md); the flags below override it")
      ->type_name("FILE");
  app.add_option("--state-dir", a.state_dir,
                 "keep the current map (snapshot + journal) and acknowledged tiles here, and "
                 "restore them at start [none: memory only]")
      ->type_name("DIR");
  app.add_option("--key-file", a.key_file,
                 "the fleet key (docs/security.md): sign what is sent, accept only messages "
                 "signed by their channel's owner; the file must be chmod 600 [none: "
                 "unauthenticated]")
      ->type_name("FILE");
  app.add_option("--uplink-url", a.uplink_url,
                 "where vehicles send [udpm://239.255.76.67:7667?ttl=0]")
      ->type_name("URL");
  app.add_option("--downlink-url", a.downlink_url,
                 "where the aggregator answers [udpm://239.255.76.68:7668?ttl=0]")
      ->type_name("URL");
  app.add_option("--final-map", a.final_map,
                 "at exit, write the current map there (map_server YAML + PGM) and a PNG "
                 "picture beside it")
      ->type_name("FILE");
  app.add_option("--duration", a.duration_s, "stop after S seconds (live) [until a signal]")
      ->check(core::NotNegative())
      ->type_name("S");
  app.add_option("--replay", a.replay,
                 "instead of listening, feed the uplink messages of these LCM logs in "
                 "event-time order, as fast as possible; publishes nothing")
      ->type_name("LOG");
  app.add_flag("--quiet", a.quiet, "no progress lines");
}

LogSink StderrLog() {
  return [](LogLevel level, const std::string& line) {
    std::fprintf(stderr, "fleetmap-aggregator: %s%s\n",
                 level == LogLevel::kWarning ? "warning: " : "", line.c_str());
  };
}

core::Result<AggregatorProcessConfig> Configure(const Args& args) {
  AggregatorProcessConfig config = DefaultProcessConfig();
  if (!args.config.empty()) FLEETMAP_ASSIGN_OR_RETURN(config, LoadProcessConfig(args.config));
  if (!args.state_dir.empty()) config.state_dir = args.state_dir;
  if (!args.uplink_url.empty()) config.uplink_url = args.uplink_url;
  if (!args.downlink_url.empty()) config.downlink_url = args.downlink_url;
  config.node.software_version = FLEETMAP_VERSION;
  if (!args.key_file.empty()) config.key_file = args.key_file;
  if (!config.key_file.empty()) {
    FLEETMAP_ASSIGN_OR_RETURN(config.node.fleet_key, auth::ReadKeyFile(config.key_file));
  } else if (!args.quiet) {
    std::fprintf(stderr, "fleetmap-aggregator: no fleet key: messages are not authenticated\n");
  }
  // Acknowledged tiles are kept only by a live run with a state folder: a replay sends no
  // acknowledgement. Likewise only a live run asks the fleet for what a recovery lost.
  if (!config.state_dir.empty() && args.replay.empty()) {
    config.node.spool_dir = config.state_dir + "/incoming";
    std::optional<aggregator::RecoveryMarker> recovery;
    FLEETMAP_ASSIGN_OR_RETURN(recovery, aggregator::ReadRecoveryMarker(config.state_dir));
    if (recovery) {
      config.node.recovery = {recovery->id, static_cast<int64_t>(recovery->version),
                              recovery->at_s + config.node.recovery_request_s};
    }
  }
  FLEETMAP_RETURN_IF_ERROR(config.Validate());
  return config;
}

core::Result<std::unique_ptr<AggregatorNode>> MakeNode(const Args& args,
                                                       const AggregatorProcessConfig& config,
                                                       Publisher* publisher, double now_s) {
  auto loaded = core::LoadMapServerMap(args.map);
  if (!loaded.ok()) return loaded.status();
  aggregator::RestoreReport restore;
  auto aggregator = config.state_dir.empty()
                        ? aggregator::Aggregator::Create(std::move(loaded->grid), config.aggregator)
                        : aggregator::Aggregator::Open(std::move(loaded->grid), config.aggregator,
                                                       config.state_dir, &restore);
  if (!aggregator.ok()) return aggregator.status();
  if (!args.quiet && !config.state_dir.empty()) {
    std::fprintf(stderr,
                 "fleetmap-aggregator: state %s: version %llu (snapshot %s, %d journal "
                 "records%s)\n",
                 config.state_dir.c_str(), (unsigned long long)aggregator->store().version(),
                 restore.snapshot_found ? "found" : "none", restore.journal_records,
                 restore.torn_tail_dropped ? ", a last record never committed dropped" : "");
  }
  return AggregatorNode::Create(std::move(aggregator).value(), config.node, publisher, StderrLog(),
                                now_s);
}

int Finish(const Args& args, const AggregatorProcessConfig& config, AggregatorNode& node) {
  int rc = 0;
  if (!config.state_dir.empty()) {
    const core::Status s = node.Snapshot();
    if (!s.ok()) std::fprintf(stderr, "fleetmap-aggregator: snapshot: %s\n", s.ToString().c_str());
  }
  if (!args.final_map.empty()) {
    const auto& map = node.aggregator().store().current_map();
    std::error_code ec;
    const auto folder = std::filesystem::path(args.final_map).parent_path();
    if (!folder.empty()) std::filesystem::create_directories(folder, ec);
    core::Status s = core::SaveMapServerMap(map, args.final_map);
    if (s.ok()) {
      s = core::RenderGridToPng(
          map, std::filesystem::path(args.final_map).replace_extension(".png").string());
    }
    if (!s.ok()) {
      std::fprintf(stderr, "fleetmap-aggregator: --final-map: %s\n", s.ToString().c_str());
      rc = 1;
    }
  }
  if (!args.quiet) {
    for (const auto& [channel, bytes] : node.largest_messages())
      std::fprintf(stderr, "fleetmap-aggregator: largest %s message %zu B\n", channel.c_str(),
                   bytes);
  }
  std::printf("%s\n", node.FinalLine().c_str());
  std::fflush(stdout);
  return rc;
}

void Progress(const AggregatorNode& node, double elapsed_s) {
  const NodeCounters& c = node.counters();
  std::fprintf(stderr,
               "fleetmap-aggregator: %.0f s: version %llu, merged %lld, rejected %lld, "
               "tiles %lld, incomplete maps %zu, requests %lld, state %s\n",
               elapsed_s, (unsigned long long)node.aggregator().store().version(),
               (long long)c.maps_merged, (long long)c.maps_rejected, (long long)c.tiles_received,
               node.incomplete_maps(), (long long)c.requests, node.state().c_str());
}

int RunReplay(const Args& args, const AggregatorProcessConfig& config) {
  auto node = MakeNode(args, config, nullptr, 0.0);
  if (!node.ok()) {
    std::fprintf(stderr, "fleetmap-aggregator: %s\n", node.status().ToString().c_str());
    return 1;
  }
  auto stats = ReplayLogs(args.replay, **node, &g_stop);
  if (!stats.ok()) {
    std::fprintf(stderr, "fleetmap-aggregator: --replay: %s\n", stats.status().ToString().c_str());
    return 1;
  }
  if (!args.quiet) {
    std::fprintf(stderr,
                 "fleetmap-aggregator: replayed %lld uplink messages over %.1f s of log (%lld "
                 "other events skipped)\n",
                 (long long)stats->fed, stats->last_s - stats->first_s, (long long)stats->skipped);
  }
  return Finish(args, config, **node);
}

int RunLive(const Args& args, const AggregatorProcessConfig& config) {
  auto links =
      AggregatorLinks::Open(config.uplink_url, config.downlink_url, config.node.DownlinkPacer());
  if (!links.ok()) {
    std::fprintf(stderr, "fleetmap-aggregator: %s\n", links.status().ToString().c_str());
    return 1;
  }
  const double start_s = WallClockS();
  auto node = MakeNode(args, config, links->get(), start_s);
  if (!node.ok()) {
    std::fprintf(stderr, "fleetmap-aggregator: %s\n", node.status().ToString().c_str());
    return 1;
  }
  (*links)->Bind(node->get());
  const AggregatorNodeOptions::Recovery& recovery = config.node.recovery;
  if (recovery.id != 0 && start_s < recovery.until_s) {
    std::fprintf(stderr,
                 "fleetmap-aggregator: this state folder was recovered at version %lld: asking "
                 "the vehicles for the merged maps they hold from later versions (for %.0f s "
                 "more)\n",
                 (long long)recovery.version, recovery.until_s - start_s);
  }
  if (!args.quiet) {
    std::fprintf(stderr, "fleetmap-aggregator: version %llu, listening on %s, answering on %s\n",
                 (unsigned long long)(*node)->aggregator().store().version(),
                 config.uplink_url.c_str(), config.downlink_url.c_str());
  }
  double next_progress_s = start_s + 5.0;
  // A progress line when something moved since the last one: tiles arrived or maps were merged
  // or rejected (a backlog still being merged after the last tile shows its end).
  std::tuple<int64_t, int64_t, int64_t> last_seen{-1, -1, -1};
  while (!g_stop) {
    // Asked keyframe tiles go as the downlink's budget allows: come back soon while they wait.
    const int timeout_ms = (*node)->sending() ? 5 : 100;
    if ((*links)->Poll(timeout_ms) < 0 && !g_stop) {
      std::fprintf(stderr, "fleetmap-aggregator: LCM receive failed on %s\n",
                   config.uplink_url.c_str());
      break;
    }
    const double now_s = WallClockS();
    (*node)->Tick(now_s);
    if (args.duration_s >= 0 && now_s - start_s >= args.duration_s) break;
    if (!args.quiet && now_s >= next_progress_s) {
      const NodeCounters& c = (*node)->counters();
      const std::tuple<int64_t, int64_t, int64_t> seen{c.tiles_received, c.maps_merged,
                                                       c.maps_rejected};
      if (seen != last_seen) Progress(**node, now_s - start_s);
      last_seen = seen;
      next_progress_s = now_s + 5.0;
    }
  }
  // What is still queued (a last delta, acks) goes out before the final line: up to 2 s.
  for (int i = 0; i < 400 && (*links)->Flush() > 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  return Finish(args, config, **node);
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  CLI::App app("", "fleetmap-aggregator");
  DefineFlags(app, args);
  if (const auto exit_status = core::ParseCommandLine(app, argc, argv)) return *exit_status;
  auto config = Configure(args);
  if (!config.ok()) {
    std::fprintf(stderr, "fleetmap-aggregator: %s\n", config.status().ToString().c_str());
    return 1;
  }
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  return args.replay.empty() ? RunLive(args, *config) : RunReplay(args, *config);
}
