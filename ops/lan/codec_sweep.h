// What the recorded map traffic would have cost with other codecs: every map tile a run sent
// (TEMPMAP_<id> tiles of temporary maps, MAP_DELTA and MAP_KEYFRAME tiles of the current
// map) is decoded and encoded again with each variant; the message's other fields stay as
// they were, so the totals are LCM payload bytes as if the run had used that codec. The
// codec is not a setting of the agent or the aggregator (core::CodecOptions defaults:
// temporary maps int8 log-odds, the current map 2-bit tri-state, both zstd level 3), hence
// offline.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "core/codec/map_codec.h"
#include "ops/lan/lan_log.h"

namespace fleetmap::ops::lan {

struct CodecVariant {
  std::string name;        // e.g. "zstd3", "raw8"
  bool one_byte_per_cell;  // true: tri-state frames become kTriState8Bit (log-odds stay int8)
  core::Compression compression;
  int level;  // zstd 1..19, zlib 1..9; ignored without compression
};

// raw8 (1 byte per cell, uncompressed, as a ROS OccupancyGrid), none (the sent packing,
// uncompressed), zlib 1/6/9, zstd 1/3/9/19.
std::vector<CodecVariant> DefaultCodecVariants();

struct ChannelGroupBytes {
  int64_t messages = 0;     // tiles that decoded
  int64_t sent_bytes = 0;   // their LCM payload bytes as recorded
  int64_t undecodable = 0;  // tiles whose message or frame did not decode (not counted)
  std::map<std::string, int64_t> bytes_by_variant;  // the same messages with recoded frames
};

// Groups "TEMPMAP" (every TEMPMAP_<id> but TEMPMAP_ACK), "MAP_DELTA", "MAP_KEYFRAME".
std::map<std::string, ChannelGroupBytes> RecodeMapMessages(
    const std::vector<LogMessage>& messages, const std::vector<CodecVariant>& variants);

// `codec.<group>.messages`, `codec.<group>.sent.bytes`, `codec.<group>.<variant>.bytes` lines.
std::string CodecFigureLines(const std::map<std::string, ChannelGroupBytes>& groups);

// The frame of `payload` encoded again with `variant`; its size, or an error.
core::Result<size_t> RecodedFrameBytes(const std::vector<uint8_t>& payload,
                                       const CodecVariant& variant);

}  // namespace fleetmap::ops::lan
