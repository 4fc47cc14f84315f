#include "vehicle_agent/retained_maps.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

namespace fleetmap::vehicle_agent {

namespace fs = std::filesystem;

std::string RetainedMaps::PathOf(int32_t sequence, int32_t version, double end_s) const {
  // Sequence, version and end in the name: Load needs no file opened.
  return options_.folder + "/tempmap_" + std::to_string(sequence) + "_v" + std::to_string(version) +
         "_e" + std::to_string(static_cast<int64_t>(std::floor(end_s))) + ".fmtm";
}

int RetainedMaps::Load() {
  if (options_.folder.empty()) return 0;
  std::error_code ec;
  int loaded = 0;
  for (const auto& entry : fs::directory_iterator(options_.folder, ec)) {
    RetainedMap m;
    long long end = 0;
    char tail = 0;
    const std::string name = entry.path().filename().string();
    if (std::sscanf(name.c_str(), "tempmap_%d_v%d_e%lld.fmtm%c", &m.sequence, &m.version, &end,
                    &tail) != 3)
      continue;
    m.end_s = static_cast<double>(end);
    m.path = entry.path().string();
    m.bytes = static_cast<int64_t>(fs::file_size(entry.path(), ec));
    if (ec) continue;
    bytes_ += m.bytes;
    maps_[m.sequence] = std::move(m);
    ++loaded;
  }
  FitBytes();
  return loaded;
}

void RetainedMaps::Keep(int32_t sequence, int32_t version, std::vector<core::TempMapTile> tiles,
                        const std::string& file) {
  if (options_.max_bytes <= 0 || tiles.empty()) {
    if (!file.empty()) fs::remove(file);
    return;
  }
  if (maps_.count(sequence)) Drop(maps_.find(sequence));
  RetainedMap m;
  m.sequence = sequence;
  m.version = version;
  m.end_s = tiles.front().end_s;
  std::error_code ec;
  if (!options_.folder.empty() && !file.empty()) {
    fs::create_directories(options_.folder, ec);
    m.path = PathOf(sequence, version, m.end_s);
    fs::rename(file, m.path, ec);
    if (ec) {  // not kept rather than kept half: a full disk must not stop the vehicle
      fs::remove(file, ec);
      return;
    }
    m.bytes = static_cast<int64_t>(fs::file_size(m.path, ec));
  } else {
    for (const core::TempMapTile& t : tiles) m.bytes += static_cast<int64_t>(t.frame.size());
    m.tiles = std::move(tiles);
  }
  bytes_ += m.bytes;
  maps_[sequence] = std::move(m);
  FitBytes();
}

void RetainedMaps::Drop(std::map<int32_t, RetainedMap>::iterator it) {
  std::error_code ec;
  if (!it->second.path.empty()) fs::remove(it->second.path, ec);
  bytes_ -= it->second.bytes;
  maps_.erase(it);
}

void RetainedMaps::FitBytes() {
  while (!maps_.empty() && bytes_ > options_.max_bytes) Drop(maps_.begin());
}

void RetainedMaps::DropEndedBefore(double latest_end_s) {
  for (auto it = maps_.begin(); it != maps_.end();) {
    auto next = std::next(it);
    if (it->second.end_s < latest_end_s - options_.retain_s) Drop(it);
    it = next;
  }
}

std::vector<RetainedMap> RetainedMaps::TakeMergedAfter(int64_t version) {
  std::vector<RetainedMap> out;
  for (auto it = maps_.begin(); it != maps_.end();) {
    if (it->second.version <= version) {
      ++it;
      continue;
    }
    bytes_ -= it->second.bytes;
    out.push_back(std::move(it->second));
    it = maps_.erase(it);
  }
  return out;
}

}  // namespace fleetmap::vehicle_agent
