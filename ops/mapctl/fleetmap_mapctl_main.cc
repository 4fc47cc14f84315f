// fleetmap-mapctl: the map's life on the server, from the aggregator's state folder
// (snapshot + journal): export, history, rollback, reset a region, promote standing changes,
// recover what a damaged folder still holds.
// The algorithms are in ops/mapctl (library fleetmap_ops_mapctl); this is files and flags.
// See --help and docs/operations.md.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "aggregator/persistence/recovery_marker.h"
#include "aggregator/persistence/state_dir_lock.h"
#include "core/command_line.h"
#include "core/image/map_render.h"
#include "core/map/map_io.h"
#include "ops/mapctl/map_edits.h"
#include "ops/mapctl/merge_summary.h"
#include "ops/mapctl/state_history.h"
#include "ops/mapctl/state_recovery.h"
#include "ops/mapctl/state_writer.h"

namespace {

using namespace fleetmap;

constexpr char kDescription[] =
    R"(The map's life, from the aggregator's state folder (snapshot.fms + journal.fmj): export,
history, rollback, reset a region, promote standing changes, recover. COMMAND --help: the
command's own help.)";
constexpr char kFooter[] =
    R"(rollback, reset-region, promote and recover refuse to run while an aggregator holds the
folder's lock (stop it first) and keep the old snapshot and journal in DIR/backup/.
Exit status: 0 done, 1 bad or corrupt data or a locked folder, 2 bad usage.)";

constexpr char kExportHelp[] =
    R"(Writes the current map, or the map as it was at version V (0: the static map), as
map_server YAML + PGM (trinary, as map_saver) and OUT.png (free white, occupied black,
unknown grey). Reads the state folder only.
)";
constexpr char kHistoryHelp[] = R"(Prints one line per merge, oldest first, after a header:
  version merged_s vehicle tempmap added removed candidates dropped x0_m y0_m x1_m y1_m
merged_s: the aggregator's clock (Unix seconds live, the log's in a replay); tempmap: the
vehicle's temporary map number; candidates/dropped: cells seen occupied once / seen free
again (not in the map yet); the box: every changed cell, map frame, metres ("-": none).
Merges made by this tool name the vehicle "mapctl". Reads the state folder only.
)";
constexpr char kRollbackHelp[] =
    R"(Makes the map at VERSION the current map: writes a snapshot holding merges 1..VERSION and
moves the old snapshot and journal to DIR/backup/. Start the aggregator again afterwards:
it serves VERSION, and vehicles holding a later version take its keyframe. Refused while an
aggregator runs on the folder.
)";
constexpr char kResetHelp[] =
    R"(Removes every semi-static obstacle and candidate whose cell centre lies in the box (map
frame, metres, corners in any order): one more version, by vehicle "mapctl", at time S
(default: now, Unix seconds). Static cells are never touched. Refused while an aggregator
runs on the folder; the old files go to DIR/backup/.
)";
constexpr char kPromoteHelp[] =
    R"(Obstacles that stand since version V (added at V or before) and/or for S seconds (added at
T - S or before; T default now, Unix seconds) become occupied cells of a new static map,
NEW.yaml + NEW.pgm. The history is rewritten without those cells (versions kept) for the
new map. Then run the aggregator with --map NEW.yaml, and give the vehicles NEW.yaml as
their --map. Refused while an aggregator runs on the folder; the old files go to
DIR/backup/.
)";

constexpr char kRecoverHelp[] =
    R"(For a state folder the aggregator refuses to start on (DATA_LOSS: a damaged journal or
snapshot). Keeps what can still be read: the snapshot's merges, then the journal's intact
records in order up to the first one that is not. Writes that as the new state and moves the
damaged files to DIR/backup/recover-vN-TIME/ (nothing is deleted). Prints the version
recovered and how many acknowledged merges after it are gone (the journal's commit block
says how many it held), and leaves DIR/recovery: the aggregator, started again, asks the
vehicles for the merged maps they keep (outbox.retain_merged_s) from later versions, and
merges them again. --dry-run: only print. A folder with nothing damaged is left as it is.
Exit status: 0 recovered (or nothing to recover), 1 unreadable folder or a write failed.
)";

struct Args {
  std::string state_dir = "/var/lib/fleetmap/aggregator";
  std::string map = "/var/lib/fleetmap/maps/static.yaml";
  std::string out;                  // export
  std::optional<uint64_t> version;  // export --at-version, rollback VERSION
  std::vector<double> box;          // reset-region X0 Y0 X1 Y1, metres
  std::optional<double> now_s;      // reset-region, promote: Unix seconds [now]
  std::optional<uint64_t> since_version;
  std::optional<double> older_than_s;
  bool dry_run = false;
};

int Fail(const core::Status& s) {
  std::fprintf(stderr, "fleetmap-mapctl: %s\n", s.ToString().c_str());
  return 1;
}

int Usage(const std::string& message) {
  std::fprintf(stderr, "fleetmap-mapctl: %s (see --help)\n", message.c_str());
  return 2;
}

double NowS() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

std::string BackupName(const std::string& command, uint64_t version) {
  return command + "-v" + std::to_string(version) + "-" +
         std::to_string(static_cast<long long>(NowS()));
}

// The static map, the history and the store at its last version.
struct Loaded {
  core::OccupancyGrid static_map;
  ops::mapctl::StateHistory history;
};

core::Result<Loaded> Load(const Args& a) {
  auto map = core::LoadMapServerMap(a.map);
  if (!map.ok()) return map.status();
  auto history = ops::mapctl::ReadStateHistory(a.state_dir);
  if (!history.ok()) return history.status();
  if (history->torn_tail) {
    std::fprintf(stderr,
                 "fleetmap-mapctl: note: the journal ends in a record never committed (%s): "
                 "ignored, as the aggregator does\n",
                 history->torn_detail.c_str());
  }
  return Loaded{std::move(map->grid), std::move(history).value()};
}

core::Status SaveWithPicture(const core::OccupancyGrid& grid, const std::string& yaml) {
  const auto folder = std::filesystem::path(yaml).parent_path();
  std::error_code ec;
  if (!folder.empty()) std::filesystem::create_directories(folder, ec);
  FLEETMAP_RETURN_IF_ERROR(core::SaveMapServerMap(grid, yaml));
  return core::RenderGridToPng(grid,
                               std::filesystem::path(yaml).replace_extension(".png").string());
}

int Export(const Args& a) {
  auto loaded = Load(a);
  if (!loaded.ok()) return Fail(loaded.status());
  const uint64_t version = a.version.value_or(loaded->history.version());
  auto store = ops::mapctl::RebuildStore(loaded->static_map, loaded->history, version);
  if (!store.ok()) return Fail(store.status());
  const core::Status s = SaveWithPicture(store->current_map(), a.out);
  if (!s.ok()) return Fail(s);
  std::printf("exported version %llu to %s (+ .pgm, .png)\n", (unsigned long long)version,
              a.out.c_str());
  return 0;
}

int History(const Args& a) {
  auto loaded = Load(a);
  if (!loaded.ok()) return Fail(loaded.status());
  std::printf("%s\n", ops::mapctl::HistoryHeader().c_str());
  for (const auto& commit : loaded->history.commits) {
    const auto summary = ops::mapctl::Summarize(commit, loaded->static_map.geometry());
    std::printf("%s\n", ops::mapctl::FormatSummary(summary).c_str());
  }
  return 0;
}

// Locks the folder, then writes `store` as its state.
int Replace(const Args& a, const aggregator::CurrentMapStore& store, const std::string& command,
            uint64_t old_version) {
  const auto backup =
      ops::mapctl::ReplaceState(a.state_dir, store, BackupName(command, old_version));
  if (!backup.ok()) return Fail(backup.status());
  std::printf("%s: state at version %llu (was %llu); the old files are in %s\n", command.c_str(),
              (unsigned long long)store.version(), (unsigned long long)old_version,
              backup->c_str());
  return 0;
}

int Rollback(const Args& a) {
  auto loaded = Load(a);
  if (!loaded.ok()) return Fail(loaded.status());
  auto store = ops::mapctl::RebuildStore(loaded->static_map, loaded->history, a.version.value());
  if (!store.ok()) return Fail(store.status());
  return Replace(a, *store, "rollback", loaded->history.version());
}

int ResetRegion(const Args& a) {
  const double now_s = a.now_s.value_or(NowS());
  auto loaded = Load(a);
  if (!loaded.ok()) return Fail(loaded.status());
  const uint64_t last = loaded->history.version();
  auto store = ops::mapctl::RebuildStore(loaded->static_map, loaded->history, last);
  if (!store.ok()) return Fail(store.status());
  const auto commit =
      ops::mapctl::ResetRegionCommit(*store, {a.box[0], a.box[1], a.box[2], a.box[3]}, now_s);
  const auto summary = ops::mapctl::Summarize(commit, loaded->static_map.geometry());
  auto applied = store->Apply(commit);
  if (!applied.ok()) return Fail(applied.status());
  std::printf("reset-region: %d obstacle cells removed, %d candidates dropped\n", summary.removed,
              summary.candidates_dropped);
  return Replace(a, *store, "reset-region", last);
}

core::Result<ops::mapctl::PromoteOptions> PromoteFlags(const Args& a) {
  ops::mapctl::PromoteOptions o;
  o.now_s = a.now_s.value_or(NowS());
  o.since_version = a.since_version;
  o.min_age_s = a.older_than_s;
  FLEETMAP_RETURN_IF_ERROR(o.Validate());
  return o;
}

// The promoted state on the new static map as the aggregator will load it from `out_map`.
core::Result<aggregator::CurrentMapStore> PromotedStore(const ops::mapctl::Promotion& p,
                                                        const std::string& out_map) {
  FLEETMAP_RETURN_IF_ERROR(SaveWithPicture(p.static_map, out_map));
  auto reloaded = core::LoadMapServerMap(out_map);
  if (!reloaded.ok()) return reloaded.status();
  aggregator::CurrentMapStore store(std::move(reloaded->grid), aggregator::StoreOptions{});
  for (const auto& commit : p.commits) {
    auto applied = store.Apply(commit);
    if (!applied.ok()) return applied.status().WithContext("rebasing the history");
  }
  return store;
}

int Promote(const Args& a) {
  auto options = PromoteFlags(a);
  if (!options.ok()) return Usage(options.status().message());
  auto loaded = Load(a);
  if (!loaded.ok()) return Fail(loaded.status());
  const uint64_t last = loaded->history.version();
  auto store = ops::mapctl::RebuildStore(loaded->static_map, loaded->history, last);
  if (!store.ok()) return Fail(store.status());
  const auto cells = ops::mapctl::StandingCells(*store, *options);
  if (cells.empty()) {
    std::printf("promote: no obstacle qualifies; nothing written\n");
    return 0;
  }
  auto promoted = PromotedStore(ops::mapctl::Promote(*store, cells), a.out);
  if (!promoted.ok()) return Fail(promoted.status());
  std::printf("promote: %zu cells are static in %s; run the aggregator with --map %s\n",
              cells.size(), a.out.c_str(), a.out.c_str());
  return Replace(a, *promoted, "promote", last);
}

void PrintRecovery(const ops::mapctl::Recovery& r) {
  if (!r.snapshot_damage.empty())
    std::printf("snapshot: damaged (%s): its merges cannot be recovered\n",
                r.snapshot_damage.c_str());
  else if (r.history.snapshot_found)
    std::printf("snapshot: version %llu, whole\n", (unsigned long long)r.history.snapshot_version);
  if (!r.journal_damage.empty()) std::printf("journal: damaged (%s)\n", r.journal_damage.c_str());
  std::printf(
      "journal: %d record(s) intact of %s committed\n", r.journal_read,
      r.journal_committed < 0 ? "an unknown number" : std::to_string(r.journal_committed).c_str());
  std::printf("recovered: version %llu (%d merges from the snapshot, %d from the journal)\n",
              (unsigned long long)r.history.version(),
              static_cast<int>(r.history.commits.size()) - r.history.journal_records,
              r.history.journal_records);
  if (r.versions_lost > 0)
    std::printf("lost: %lld acknowledged merge(s) after version %llu\n", (long long)r.versions_lost,
                (unsigned long long)r.history.version());
  else if (r.versions_lost < 0)
    std::printf("lost: an unknown number of acknowledged merges after version %llu\n",
                (unsigned long long)r.history.version());
}

int Recover(const Args& a) {
  auto map = core::LoadMapServerMap(a.map);
  if (!map.ok()) return Fail(map.status());
  auto recovery = ops::mapctl::ReadRecoverableHistory(a.state_dir);
  if (!recovery.ok()) return Fail(recovery.status());
  if (!recovery->damaged()) {
    std::printf("recover: nothing damaged: the aggregator opens %s as it is (version %llu)\n",
                a.state_dir.c_str(), (unsigned long long)recovery->history.version());
    return 0;
  }
  PrintRecovery(*recovery);
  auto store = ops::mapctl::RebuildStore(map->grid, recovery->history, recovery->history.version());
  if (!store.ok()) return Fail(store.status());
  if (a.dry_run) {
    std::printf("recover: --dry-run: nothing written\n");
    return 0;
  }
  const uint64_t version = recovery->history.version();
  const auto backup =
      ops::mapctl::ReplaceState(a.state_dir, *store, BackupName("recover", version));
  if (!backup.ok()) return Fail(backup.status());
  std::printf("recover: state at version %llu; the damaged files are in %s\n",
              (unsigned long long)version, backup->c_str());
  const double now_s = NowS();
  const aggregator::RecoveryMarker marker{static_cast<int64_t>(now_s * 1e6), version, now_s};
  const core::Status marked = aggregator::WriteRecoveryMarker(a.state_dir, marker);
  if (!marked.ok()) return Fail(marked);
  std::printf(
      "recover: once started, the aggregator asks the vehicles for the merged maps they hold "
      "from versions after %llu (node.recovery_request_s)\n",
      (unsigned long long)version);
  return 0;
}

// Reads a flag into an optional, set only when given (CLI11 2.1 cannot fill std::optional).
template <typename T>
CLI::Option* AddOptional(CLI::App* app, const std::string& name, std::optional<T>& value,
                         const std::string& help) {
  return app->add_option_function<T>(
      name, [&value](const T& v) { value = v; }, help);
}

// One subcommand: its help, what it runs, whether it writes the state folder.
struct Command {
  CLI::App* app;
  int (*run)(const Args&);
  bool writes;
};

std::vector<Command> DefineCommands(CLI::App& app, Args& a) {
  app.description(kDescription);
  app.footer(kFooter);
  core::AddVersionFlag(app);
  app.require_subcommand(1);
  app.fallthrough();  // the common flags also after the command
  app.add_option("--state-dir", a.state_dir, "the aggregator's state folder")
      ->type_name("DIR")
      ->capture_default_str();
  app.add_option("--map", a.map, "the static map the aggregator runs with, its --map")
      ->type_name("FILE")
      ->capture_default_str();
  CLI::App* export_map =
      app.add_subcommand("export", "the current map (or version V) as map_server YAML + PGM");
  export_map->footer(kExportHelp);
  export_map->add_option("OUT.yaml", a.out, "the map to write")->required();
  AddOptional(export_map, "--at-version", a.version, "the map as it was at version V")
      ->type_name("V")
      ->check(core::WholeNumber());
  CLI::App* history = app.add_subcommand("history", "one line per merge");
  history->footer(kHistoryHelp);
  CLI::App* rollback = app.add_subcommand("rollback", "make VERSION the current map");
  rollback->footer(kRollbackHelp);
  AddOptional(rollback, "VERSION", a.version, "the version")
      ->required()
      ->check(core::WholeNumber());
  CLI::App* reset = app.add_subcommand(
      "reset-region", "semi-static changes in the box (metres) back to the static map");
  reset->footer(kResetHelp);
  reset->add_option("X0 Y0 X1 Y1", a.box, "the box, metres")
      ->expected(4)
      ->required()
      ->check(core::Finite());
  AddOptional(reset, "--now", a.now_s, "the time of the change, Unix seconds [now]")
      ->check(core::Finite());
  CLI::App* promote = app.add_subcommand("promote", "obstacles standing long enough become static");
  promote->footer(kPromoteHelp);
  promote->add_option("--out-map", a.out, "the new static map")->required()->type_name("NEW.yaml");
  AddOptional(promote, "--since-version", a.since_version, "standing since version V")
      ->type_name("V")
      ->check(core::WholeNumber());
  AddOptional(promote, "--older-than", a.older_than_s, "standing for S seconds")
      ->type_name("S")
      ->check(core::NotNegative());
  AddOptional(promote, "--now", a.now_s, "Unix seconds [now]")->check(core::Finite());
  CLI::App* recover = app.add_subcommand("recover",
                                         "after DATA_LOSS at the aggregator's start: keep what can "
                                         "still be read, report what is gone");
  recover->footer(kRecoverHelp);
  recover->add_flag("--dry-run", a.dry_run, "only print");
  return {{export_map, Export, false}, {history, History, false}, {rollback, Rollback, true},
          {reset, ResetRegion, true},  {promote, Promote, true},  {recover, Recover, true}};
}

int Run(const Args& a, const std::vector<Command>& commands) {
  for (const Command& c : commands) {
    if (!c.app->parsed()) continue;
    if (!c.writes) return c.run(a);
    // Held until the new state is written: no aggregator can start on the folder meanwhile.
    auto lock = aggregator::StateDirLock::Acquire(a.state_dir);
    if (!lock.ok()) return Fail(lock.status());
    return c.run(a);
  }
  return Usage("no command");
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  CLI::App app("", "fleetmap-mapctl");
  const std::vector<Command> commands = DefineCommands(app, args);
  if (const auto exit_status = core::ParseCommandLine(app, argc, argv)) return *exit_status;
  return Run(args, commands);
}
