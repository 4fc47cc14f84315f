#include "ops/lan/codec_sweep.h"

#include <unordered_map>

#include "auth/trailer.h"
#include "fleetmap/map_delta_t.hpp"
#include "fleetmap/map_keyframe_t.hpp"
#include "fleetmap/tempmap_tile_t.hpp"
#include "lcmtypes/convert.h"

namespace fleetmap::ops::lan {
namespace {

// The group of a channel, or nullptr for channels that carry no map tile.
const char* GroupOf(const std::string& channel) {
  if (channel == lcmtypes::kMapDeltaChannel) return "MAP_DELTA";
  if (channel == lcmtypes::kMapKeyframeChannel) return "MAP_KEYFRAME";
  if (lcmtypes::IsTempMapTileChannel(channel)) return "TEMPMAP";
  return nullptr;
}

// The codec frame a map message carries.
core::Result<std::vector<uint8_t>> FrameOf(const std::string& group, const LogMessage& m) {
  // The message without the trailer that names its sender (auth/trailer.h).
  const int size = static_cast<int>(auth::PayloadSize(m.data.data(), m.data.size()));
  if (group == "TEMPMAP") {
    auto t = lcmtypes::Decode<fleetmap::tempmap_tile_t>(m.data.data(), size);
    if (!t.ok()) return t.status();
    return t->tile.payload;
  }
  if (group == "MAP_DELTA") {
    auto t = lcmtypes::Decode<fleetmap::map_delta_t>(m.data.data(), size);
    if (!t.ok()) return t.status();
    return t->tile.payload;
  }
  auto t = lcmtypes::Decode<fleetmap::map_keyframe_t>(m.data.data(), size);
  if (!t.ok()) return t.status();
  return t->tile.payload;
}

}  // namespace

std::vector<CodecVariant> DefaultCodecVariants() {
  using core::Compression;
  return {{"raw8", true, Compression::kNone, 0},    {"none", false, Compression::kNone, 0},
          {"zlib1", false, Compression::kZlib, 1},  {"zlib6", false, Compression::kZlib, 6},
          {"zlib9", false, Compression::kZlib, 9},  {"zstd1", false, Compression::kZstd, 1},
          {"zstd3", false, Compression::kZstd, 3},  {"zstd9", false, Compression::kZstd, 9},
          {"zstd19", false, Compression::kZstd, 19}};
}

core::Result<size_t> RecodedFrameBytes(const std::vector<uint8_t>& payload,
                                       const CodecVariant& variant) {
  auto frame = core::DecodeFrame(payload);
  if (!frame.ok()) return frame.status();
  const core::CellWindow& w = frame->window;
  // The window alone, as a grid of its own: the frame's header is the same size wherever
  // the window lies.
  core::OccupancyGrid grid(core::GridGeometry(1.0, w.width, w.height));
  const core::CellWindow local{0, 0, w.width, w.height};
  core::WriteCells(frame->values, frame->packing, local, grid);
  core::CodecOptions options;
  options.packing = frame->packing;
  if (variant.one_byte_per_cell && frame->packing == core::CellPacking::kTriState2Bit)
    options.packing = core::CellPacking::kTriState8Bit;
  options.compression = variant.compression;
  options.level = variant.level > 0 ? variant.level : 3;
  return core::EncodeWindow(grid, local, options).size();
}

std::map<std::string, ChannelGroupBytes> RecodeMapMessages(
    const std::vector<LogMessage>& messages, const std::vector<CodecVariant>& variants) {
  std::map<std::string, ChannelGroupBytes> groups;
  // Resent tiles and periodic keyframes repeat frames: encode each distinct frame once.
  std::unordered_map<std::string, std::vector<int64_t>> recoded_by_frame;
  for (const LogMessage& m : messages) {
    const char* group = GroupOf(m.channel);
    if (!group) continue;
    ChannelGroupBytes& g = groups[group];
    auto frame = FrameOf(group, m);
    if (!frame.ok()) {
      ++g.undecodable;
      continue;
    }
    const std::string key(frame->begin(), frame->end());
    auto it = recoded_by_frame.find(key);
    if (it == recoded_by_frame.end()) {
      std::vector<int64_t> sizes;
      for (const CodecVariant& v : variants) {
        auto bytes = RecodedFrameBytes(*frame, v);
        if (!bytes.ok()) break;
        sizes.push_back(static_cast<int64_t>(*bytes));
      }
      it = recoded_by_frame.emplace(key, std::move(sizes)).first;
    }
    if (it->second.size() != variants.size()) {
      ++g.undecodable;
      continue;
    }
    ++g.messages;
    const int64_t sent = static_cast<int64_t>(m.data.size());
    const int64_t other = sent - static_cast<int64_t>(frame->size());
    g.sent_bytes += sent;
    for (size_t i = 0; i < variants.size(); ++i)
      g.bytes_by_variant[variants[i].name] += other + it->second[i];
  }
  return groups;
}

std::string CodecFigureLines(const std::map<std::string, ChannelGroupBytes>& groups) {
  std::string out;
  for (const auto& [group, g] : groups) {
    const std::string prefix = "codec." + group + ".";
    out += prefix + "messages " + std::to_string(g.messages) + " count\n";
    out += prefix + "undecodable " + std::to_string(g.undecodable) + " count\n";
    out += prefix + "sent.bytes " + std::to_string(g.sent_bytes) + " B\n";
    for (const auto& [variant, bytes] : g.bytes_by_variant)
      out += prefix + variant + ".bytes " + std::to_string(bytes) + " B\n";
  }
  return out;
}

}  // namespace fleetmap::ops::lan
