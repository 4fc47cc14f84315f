#include "aggregator/node/tile_spool.h"

#include <algorithm>
#include <filesystem>
#include <optional>

#include "core/io/file_io.h"

namespace fleetmap::aggregator::node {
namespace {

namespace fs = std::filesystem;

constexpr const char* kSuffix = ".tile";
constexpr int64_t kMaxTileFileBytes = 1 << 20;

// Vehicle ids come from the network: hex keeps any of them a safe file name.
std::string Hex(const std::string& s) {
  static const char* kDigits = "0123456789abcdef";
  std::string out;
  for (unsigned char c : s) {
    out.push_back(kDigits[c >> 4]);
    out.push_back(kDigits[c & 15]);
  }
  return out;
}

std::optional<std::string> Unhex(const std::string& s) {
  if (s.empty() || s.size() % 2) return std::nullopt;
  auto value = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    return -1;
  };
  std::string out;
  for (size_t i = 0; i < s.size(); i += 2) {
    const int hi = value(s[i]), lo = value(s[i + 1]);
    if (hi < 0 || lo < 0) return std::nullopt;
    out.push_back(static_cast<char>(hi * 16 + lo));
  }
  return out;
}

std::optional<int32_t> ParseInt(const std::string& s) {
  if (s.empty() || s.size() > 11) return std::nullopt;
  try {
    size_t used = 0;
    const long long v = std::stoll(s, &used);
    if (used != s.size() || v < INT32_MIN || v > INT32_MAX) return std::nullopt;
    return static_cast<int32_t>(v);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// "<hex>.<sequence>.<index>.tile" -> key and index.
std::optional<std::pair<MapKey, int32_t>> ParseName(const std::string& name) {
  const std::string suffix = kSuffix;
  if (name.size() <= suffix.size() ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) {
    return std::nullopt;
  }
  const std::string stem = name.substr(0, name.size() - suffix.size());
  const size_t dot2 = stem.rfind('.');
  if (dot2 == std::string::npos || dot2 == 0) return std::nullopt;
  const size_t dot1 = stem.rfind('.', dot2 - 1);
  if (dot1 == std::string::npos) return std::nullopt;
  auto vehicle = Unhex(stem.substr(0, dot1));
  auto sequence = ParseInt(stem.substr(dot1 + 1, dot2 - dot1 - 1));
  auto index = ParseInt(stem.substr(dot2 + 1));
  if (!vehicle || !sequence || !index) return std::nullopt;
  return std::make_pair(MapKey{*vehicle, *sequence}, *index);
}

}  // namespace

core::Result<TileSpool> TileSpool::Open(const std::string& folder) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec || !fs::is_directory(folder, ec)) {
    return core::IoError("cannot create the tile spool folder " + folder + ": " + ec.message());
  }
  return TileSpool(folder);
}

std::string TileSpool::PathOf(const MapKey& key, int32_t index) const {
  return folder_ + "/" + Hex(key.vehicle_id) + "." + std::to_string(key.sequence) + "." +
         std::to_string(index) + kSuffix;
}

core::Status TileSpool::Save(const MapKey& key, int32_t index, const std::vector<uint8_t>& bytes) {
  if (!enabled()) return core::FailedPrecondition("the tile spool is disabled");
  FLEETMAP_RETURN_IF_ERROR(core::WriteFileAtomically(
      PathOf(key, index),
      std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size())));
  saved_[key].insert(index);
  return core::OkStatus();
}

bool TileSpool::Has(const MapKey& key, int32_t index) const {
  auto it = saved_.find(key);
  return it != saved_.end() && it->second.count(index);
}

void TileSpool::Remove(const MapKey& key) {
  auto it = saved_.find(key);
  if (it == saved_.end()) return;
  std::error_code ec;
  for (int32_t index : it->second) fs::remove(PathOf(key, index), ec);
  saved_.erase(it);
}

std::vector<SpooledTile> TileSpool::LoadAll(int* bad_files) {
  std::vector<SpooledTile> tiles;
  if (!enabled()) return tiles;
  std::error_code ec;
  std::vector<fs::path> paths;
  for (const auto& entry : fs::directory_iterator(folder_, ec)) paths.push_back(entry.path());
  std::sort(paths.begin(), paths.end());
  for (const fs::path& path : paths) {
    auto parsed = ParseName(path.filename().string());
    if (!parsed) continue;
    auto bytes = core::ReadFileBytes(path.string(), kMaxTileFileBytes);
    if (!bytes.ok()) {
      if (bad_files) ++*bad_files;
      fs::rename(path, path.string() + ".bad", ec);
      continue;
    }
    saved_[parsed->first].insert(parsed->second);
    tiles.push_back(
        {parsed->first, parsed->second, std::vector<uint8_t>(bytes->begin(), bytes->end())});
  }
  std::stable_sort(tiles.begin(), tiles.end(), [](const SpooledTile& a, const SpooledTile& b) {
    return a.key < b.key || (a.key == b.key && a.index < b.index);
  });
  return tiles;
}

}  // namespace fleetmap::aggregator::node
