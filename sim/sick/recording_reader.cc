#include "sim/sick/recording_reader.h"

#include <nlohmann/json.hpp>

#include "core/io/file_io.h"
#include "core/io/number_text.h"
#include "drivers/sick/scan_telegram_codec.h"
#include "sim/sick/tcp_reassembly.h"

namespace fleetmap::sim::sick {
namespace {

using drivers::sick::ColaProtocol;
using drivers::sick::TelegramSplitter;
using drivers::sick::TelegramSplitterOptions;
using drivers::sick::TelegramSplitterStats;

constexpr int64_t kMaxRecordingBytes = int64_t{256} << 20;

ColaProtocol DetectProtocol(const std::string& stream) {
  return stream.rfind("\x02\x02\x02\x02", 0) == 0 ? ColaProtocol::kColaB : ColaProtocol::kColaA;
}

void AddStats(TelegramSplitterStats& sum, const TelegramSplitterStats& s) {
  sum.telegrams += s.telegrams;
  sum.garbage_bytes += s.garbage_bytes;
  sum.bad_checksums += s.bad_checksums;
  sum.oversized += s.oversized;
}

// Host requests are sRN, sWN, sMN, sEN; everything else comes from the scanner.
bool FromScanner(const std::string& payload) {
  return !(payload.size() >= 3 && payload[0] == 's' &&
           (payload.compare(1, 2, "RN") == 0 || payload.compare(1, 2, "WN") == 0 ||
            payload.compare(1, 2, "MN") == 0 || payload.compare(1, 2, "EN") == 0));
}

// Splits one byte stream (or one framed telegram) into payloads.
void SplitInto(const std::string& bytes, double time_s, Recording& out) {
  TelegramSplitterOptions options;
  options.protocol = DetectProtocol(bytes);
  TelegramSplitter splitter(options);
  splitter.Feed(bytes);
  while (std::optional<std::string> payload = splitter.Next()) {
    RecordedTelegram t;
    t.time_s = time_s;
    t.protocol = options.protocol;
    t.from_scanner = FromScanner(*payload);
    t.payload = std::move(*payload);
    out.telegrams.push_back(std::move(t));
  }
  AddStats(out.framing, splitter.stats());
}

// Feeds a reassembled stream segment by segment: each telegram gets the capture time of the
// segment that completed it.
void SplitSegments(const TcpStream& stream, Recording& out) {
  if (stream.segments.empty()) return;
  TelegramSplitterOptions options;
  options.protocol = DetectProtocol(stream.segments.front().bytes);
  TelegramSplitter splitter(options);
  for (const TcpSegment& segment : stream.segments) {
    splitter.Feed(segment.bytes);
    while (std::optional<std::string> payload = splitter.Next()) {
      RecordedTelegram t;
      t.time_s = segment.time_s;
      t.protocol = options.protocol;
      t.from_scanner = FromScanner(*payload);
      t.payload = std::move(*payload);
      out.telegrams.push_back(std::move(t));
    }
  }
  AddStats(out.framing, splitter.stats());
}

core::Result<std::string> HexColons(const std::string& text) {
  std::string out;
  out.reserve(text.size() / 3 + 1);
  int nibble = -1;
  for (const char c : text) {
    if (c == ':') continue;
    int d;
    if (c >= '0' && c <= '9')
      d = c - '0';
    else if (c >= 'a' && c <= 'f')
      d = c - 'a' + 10;
    else if (c >= 'A' && c <= 'F')
      d = c - 'A' + 10;
    else
      return core::InvalidArgument("tcp.payload has a non-hex character");
    if (nibble < 0) {
      nibble = d;
    } else {
      out.push_back(static_cast<char>((nibble << 4) | d));
      nibble = -1;
    }
  }
  if (nibble >= 0) return core::InvalidArgument("tcp.payload has an odd number of hex digits");
  return out;
}

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

core::Result<Recording> ReadPcapJson(const std::string& path) {
  core::Result<std::string> text = core::ReadFileBytes(path, kMaxRecordingBytes);
  if (!text.ok()) return text.status();
  const nlohmann::json doc = nlohmann::json::parse(*text, nullptr, /*allow_exceptions=*/false);
  if (doc.is_discarded() || !doc.is_array())
    return core::InvalidArgument(path + ": not a JSON array");
  Recording out;
  for (const nlohmann::json& entry : doc) {
    const nlohmann::json* tcp = nullptr;
    if (entry.contains("_source") && entry["_source"].contains("layers") &&
        entry["_source"]["layers"].contains("tcp")) {
      tcp = &entry["_source"]["layers"]["tcp"];
    }
    if (tcp == nullptr || !tcp->contains("tcp.payload") || !(*tcp)["tcp.payload"].is_string()) {
      return core::InvalidArgument(path + ": entry without _source.layers.tcp.tcp.payload");
    }
    double time_s = 0.0;
    if (tcp->contains("Timestamps") && (*tcp)["Timestamps"].contains("tcp.time_relative")) {
      // A garbled time must not become 0 s silently: it would reorder the recording.
      const nlohmann::json& relative = (*tcp)["Timestamps"]["tcp.time_relative"];
      if (!relative.is_string())
        return core::InvalidArgument(path + ": tcp.time_relative is not a string");
      core::Result<double> parsed =
          core::ParseNumber(relative.get<std::string>(), "tcp.time_relative");
      if (!parsed.ok()) return parsed.status().WithContext(path);
      time_s = *parsed;
    }
    core::Result<std::string> bytes = HexColons((*tcp)["tcp.payload"].get<std::string>());
    if (!bytes.ok()) return bytes.status().WithContext(path);
    SplitInto(*bytes, time_s, out);
  }
  return out;
}

core::Result<Recording> ReadPysicktimDump(const std::string& path) {
  core::Result<std::string> text = core::ReadFileBytes(path, kMaxRecordingBytes);
  if (!text.ok()) return text.status();
  // Each reply is "sRA LMDscandata ..." up to the next ETX (STX may be stripped in the file).
  Recording out;
  std::string framed;
  for (size_t pos = text->find("sRA LMDscandata"); pos != std::string::npos;
       pos = text->find("sRA LMDscandata", pos + 1)) {
    const size_t end = text->find('\x03', pos);
    framed += drivers::sick::FrameColaA(std::string_view(*text).substr(
        pos, end == std::string::npos ? std::string::npos : end - pos));
  }
  SplitInto(framed, 0.0, out);
  return out;
}

core::Result<Recording> ReadPcapng(const std::string& path) {
  core::Result<std::string> bytes = core::ReadFileBytes(path, kMaxRecordingBytes);
  if (!bytes.ok()) return bytes.status();
  core::Result<std::vector<TcpStream>> streams = ReassemblePcapng(*bytes);
  if (!streams.ok()) return streams.status().WithContext(path);
  Recording out;
  for (const TcpStream& stream : *streams) SplitSegments(stream, out);
  return out;
}

core::Result<Recording> ReadRecording(const std::string& path) {
  if (EndsWith(path, ".json")) return ReadPcapJson(path);
  if (EndsWith(path, ".pcapng")) return ReadPcapng(path);
  if (EndsWith(path, ".dat")) return ReadPysicktimDump(path);
  return core::InvalidArgument(path + ": unknown recording type (.pcapng, .pcapng.json, .dat)");
}

std::vector<RecordedTelegram> ScanTelegrams(const Recording& recording) {
  std::vector<RecordedTelegram> scans;
  for (const RecordedTelegram& t : recording.telegrams) {
    if (t.from_scanner && drivers::sick::IsScanTelegram(t.payload)) scans.push_back(t);
  }
  return scans;
}

}  // namespace fleetmap::sim::sick
