#include "vehicle_agent/tempmap_outbox.h"

#include <algorithm>
#include <filesystem>

#include "core/map/temp_map_file.h"

namespace fleetmap::vehicle_agent {

namespace fs = std::filesystem;

core::Status OutboxOptions::Validate() const {
  if (!(first_resend_s > 0 && max_resend_s >= first_resend_s && max_pending_maps >= 1 &&
        tile_size_cells >= 4 && retain_merged_s >= 0 && max_retained_bytes >= 0)) {
    return core::InvalidArgument(
        "outbox: first_resend_s > 0, max_resend_s >= first_resend_s, "
        "max_pending_maps >= 1, tile_size_cells >= 4, retain_merged_s >= 0, "
        "max_retained_bytes >= 0");
  }
  return core::OkStatus();
}

TempMapOutbox::TempMapOutbox(const OutboxOptions& options)
    : options_(options),
      retained_({options.state_dir.empty() ? "" : options.state_dir + "/retained",
                 options.retain_merged_s, options.max_retained_bytes}) {}

std::string TempMapOutbox::PathOf(int32_t sequence) const {
  return options_.state_dir + "/tempmap_" + std::to_string(sequence) + ".fmtm";
}

void TempMapOutbox::Insert(const core::TempMap& map, double now_s) {
  InsertTiles(map.sequence,
              core::SplitTempMap(map, core::TempMapTileOptions(options_.tile_size_cells)), now_s);
}

void TempMapOutbox::InsertTiles(int32_t sequence, std::vector<core::TempMapTile> tiles,
                                double now_s) {
  Entry e;
  e.tiles = std::move(tiles);
  e.next_send_s = now_s;
  e.backoff_s = options_.first_resend_s;
  pending_[sequence] = std::move(e);
  while (static_cast<int>(pending_.size()) > options_.max_pending_maps) {
    const int32_t oldest = pending_.begin()->first;
    if (!options_.state_dir.empty()) fs::remove(PathOf(oldest));
    pending_.erase(pending_.begin());
    ++counters_.maps_dropped;
  }
}

int TempMapOutbox::LoadPersisted(double now_s) {
  if (options_.state_dir.empty()) return 0;
  std::error_code ec;
  fs::create_directories(options_.state_dir, ec);
  int loaded = 0;
  for (const auto& entry : fs::directory_iterator(options_.state_dir, ec)) {
    if (entry.path().extension() != ".fmtm") continue;
    auto map = core::LoadTempMap(entry.path().string());
    if (!map.ok()) {
      ++counters_.persist_errors;
      fs::rename(entry.path(), entry.path().string() + ".corrupt", ec);
      continue;
    }
    Insert(*map, now_s);
    ++loaded;
  }
  retained_.Load();
  return loaded;
}

core::Status TempMapOutbox::Add(const core::TempMap& map, double now_s) {
  FLEETMAP_RETURN_IF_ERROR(map.Validate());
  ++counters_.maps_added;
  if (!options_.state_dir.empty()) {
    std::error_code ec;
    fs::create_directories(options_.state_dir, ec);
    // Kept for a restarted agent, not for a power loss: no fsync. This runs on the scan loop,
    // and fsync can stall it for seconds on a busy disk (in an ASan fleet test right after a
    // build, both agents closing their first map stopped for 6.7 s and lost their pose). A map
    // lost with the power is seen again on the next pass.
    const core::Status saved =
        core::SaveTempMap(map, PathOf(map.sequence), core::Durability::kProcessCrash);
    // A full disk must not stop the map from being sent: it is only not kept across restarts.
    if (!saved.ok()) ++counters_.persist_errors;
  }
  retained_.DropEndedBefore(map.end_s);
  Insert(map, now_s);
  return core::OkStatus();
}

std::vector<core::TempMapTile> TempMapOutbox::Due(double now_s) {
  std::vector<core::TempMapTile> out;
  for (auto& [sequence, e] : pending_) {
    if (now_s < e.next_send_s) continue;
    for (const core::TempMapTile& t : e.tiles) {
      if (e.confirmed.count(t.index)) continue;
      out.push_back(t);
      (e.sent_once ? counters_.tiles_resent : counters_.tiles_sent)++;
    }
    e.sent_once = true;
    e.last_send_s = now_s;
    e.next_send_s = now_s + e.backoff_s;
    e.backoff_s = std::min(options_.max_resend_s, 2 * e.backoff_s);
  }
  return out;
}

void TempMapOutbox::OnAck(int32_t sequence, const std::vector<int32_t>& received,
                          AckOutcome outcome, int32_t map_version) {
  auto it = pending_.find(sequence);
  if (it == pending_.end()) return;
  if (outcome != AckOutcome::kPending) {
    const std::string file = options_.state_dir.empty() ? "" : PathOf(sequence);
    const bool merged = outcome == AckOutcome::kMerged || outcome == AckOutcome::kDuplicate;
    if (merged && map_version >= 1) {
      retained_.Keep(sequence, map_version, std::move(it->second.tiles), file);
    } else if (!file.empty()) {
      fs::remove(file);
    }
    pending_.erase(it);
    ++counters_.maps_done;
    return;
  }
  Entry& e = it->second;
  const size_t before = e.confirmed.size();
  for (int32_t i : received) e.confirmed.insert(i);
  if (e.confirmed.size() > before) {
    // Tiles got through: the aggregator is there and the link only loses some. The backoff is
    // for an aggregator that is away; on a lossy link it would wait 2, 4, 8 s between rounds
    // for the last few tiles (docs/experiments/2026-12-01-lossy-links.md).
    e.backoff_s = options_.first_resend_s;
    e.next_send_s = std::min(e.next_send_s, e.last_send_s + options_.first_resend_s);
  }
}

int TempMapOutbox::ResendMergedAfter(int64_t version, double now_s) {
  int resent = 0;
  for (RetainedMap& m : retained_.TakeMergedAfter(version)) {
    if (m.path.empty()) {
      InsertTiles(m.sequence, std::move(m.tiles), now_s);
    } else {
      auto map = core::LoadTempMap(m.path);
      std::error_code ec;
      if (!map.ok()) {
        ++counters_.persist_errors;
        fs::rename(m.path, m.path + ".corrupt", ec);
        continue;
      }
      fs::rename(m.path, PathOf(m.sequence), ec);  // pending again, also across a restart
      Insert(*map, now_s);
    }
    ++resent;
  }
  counters_.maps_resent_after_recovery += resent;
  return resent;
}

}  // namespace fleetmap::vehicle_agent
