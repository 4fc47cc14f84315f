#include "drivers/can/candump_log.h"

#include <cmath>
#include <cstdio>

#include "core/io/file_io.h"

namespace fleetmap::drivers::can {
namespace {

constexpr size_t kMaxErrorsKept = 10;

int HexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

core::Result<double> ParseStamp(std::string_view t) {
  // "(seconds.fraction)"
  if (t.size() < 3 || t.front() != '(' || t.back() != ')') {
    return core::InvalidArgument("timestamp must look like (1649249898.730936)");
  }
  t = t.substr(1, t.size() - 2);
  const size_t dot = t.find('.');
  double seconds = 0.0, scale = 1.0, fraction = 0.0;
  for (size_t i = 0; i < t.size(); ++i) {
    if (i == dot) continue;
    if (t[i] < '0' || t[i] > '9' || i > 24) return core::InvalidArgument("bad timestamp digits");
    if (dot == std::string_view::npos || i < dot) {
      seconds = seconds * 10 + (t[i] - '0');
    } else {
      scale *= 0.1;
      fraction += (t[i] - '0') * scale;
    }
  }
  // candump writes seconds since the epoch. Beyond 1e12 s (year 33658) a stamp is corrupt, and
  // FormatCandumpLine could not write it back: 19 integer digits no longer fit the 25
  // characters read here, and 1e19 s not a long long.
  const double stamp_s = seconds + fraction;
  if (stamp_s >= 1e12) return core::InvalidArgument("timestamp out of range");
  return stamp_s;
}

core::Status ParseData(std::string_view d, CanFrame& f) {
  size_t n = 0;
  for (size_t i = 0; i < d.size();) {
    if (d[i] == '.') {
      ++i;
      continue;
    }
    const int hi = HexDigit(d[i]), lo = i + 1 < d.size() ? HexDigit(d[i + 1]) : -1;
    if (hi < 0 || lo < 0) return core::InvalidArgument("data must be pairs of hex digits");
    if (n >= (f.fd ? 64u : 8u)) return core::InvalidArgument("too many data bytes");
    f.data[n++] = static_cast<uint8_t>(hi << 4 | lo);
    i += 2;
  }
  f.len = static_cast<uint8_t>(n);
  return core::OkStatus();
}

core::Status ParseId(std::string_view id, CanFrame& f) {
  if (id.size() != 3 && id.size() != 8) {
    return core::InvalidArgument("id must have 3 (standard) or 8 (extended) hex digits");
  }
  uint32_t v = 0;
  for (const char c : id) {
    const int d = HexDigit(c);
    if (d < 0) return core::InvalidArgument("id is not hex");
    v = v << 4 | static_cast<uint32_t>(d);
  }
  f.error = id.size() == 8 && (v & 0x20000000u);
  f.extended = id.size() == 8 && !f.error;
  f.id = v & (f.error ? kCanErrorClassMask : 0xFFFFFFFFu);
  return core::OkStatus();
}

// Everything after '#': data, R[len], or for FD "#<flags><data>"; an optional "_<dlc>".
core::Status ParsePayload(std::string_view p, CanFrame& f) {
  if (!p.empty() && p[0] == '#') {
    f.fd = true;
    if (p.size() < 2 || HexDigit(p[1]) < 0) return core::InvalidArgument("FD frame lacks flags");
    // Newer kernels also report CANFD_FDF (0x04) here; only BRS and ESI are frame flags.
    f.fd_flags =
        static_cast<uint8_t>(HexDigit(p[1]) & (kCanFdBitRateSwitch | kCanFdErrorStateIndicator));
    return ParseData(p.substr(2), f);
  }
  if (const size_t u = p.find('_'); u != std::string_view::npos) {
    if (u + 2 != p.size() || HexDigit(p[u + 1]) < 9) return core::InvalidArgument("bad _dlc");
    f.len8_dlc = static_cast<uint8_t>(HexDigit(p[u + 1]));
    p = p.substr(0, u);
  }
  if (!p.empty() && (p[0] == 'R' || p[0] == 'r')) {
    f.rtr = true;
    if (p.size() > 2 || (p.size() == 2 && (HexDigit(p[1]) < 0 || HexDigit(p[1]) > 8))) {
      return core::InvalidArgument("bad RTR length");
    }
    f.len = p.size() == 2 ? static_cast<uint8_t>(HexDigit(p[1])) : 0;
    return core::OkStatus();
  }
  return ParseData(p, f);
}

}  // namespace

core::Result<CandumpRecord> ParseCandumpLine(std::string_view line) {
  while (!line.empty() && (line.back() == '\r' || line.back() == '\n' || line.back() == ' ')) {
    line.remove_suffix(1);
  }
  const size_t s1 = line.find(' ');
  const size_t s2 = s1 == std::string_view::npos ? s1 : line.find(' ', s1 + 1);
  if (s2 == std::string_view::npos) return core::InvalidArgument("expected '(time) iface ID#DATA'");
  CandumpRecord r;
  core::Result<double> stamp = ParseStamp(line.substr(0, s1));
  if (!stamp.ok()) return stamp.status();
  r.frame.stamp_s = *stamp;
  r.interface = std::string(line.substr(s1 + 1, s2 - s1 - 1));
  std::string_view frame = line.substr(s2 + 1);
  if (const size_t extra = frame.find(' '); extra != std::string_view::npos) {
    frame = frame.substr(0, extra);  // candump -L may append a direction flag
  }
  const size_t hash = frame.find('#');
  if (hash == std::string_view::npos) return core::InvalidArgument("frame lacks '#'");
  FLEETMAP_RETURN_IF_ERROR(ParseId(frame.substr(0, hash), r.frame));
  FLEETMAP_RETURN_IF_ERROR(ParsePayload(frame.substr(hash + 1), r.frame));
  FLEETMAP_RETURN_IF_ERROR(r.frame.Validate());
  return r;
}

std::string FormatCandumpLine(const CandumpRecord& record) {
  const double t = record.frame.stamp_s;
  long long seconds = static_cast<long long>(std::floor(t));
  long long micros = std::llround((t - static_cast<double>(seconds)) * 1e6);
  if (micros >= 1000000) seconds += 1, micros -= 1000000;
  char stamp[48];
  std::snprintf(stamp, sizeof(stamp), "(%010lld.%06lld) ", seconds, micros);
  return stamp + record.interface + " " + record.frame.ToString();
}

CandumpLog ParseCandumpLog(std::string_view text) {
  CandumpLog log;
  size_t pos = 0;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++log.stats.lines;
    if (line.empty() || line[0] != '(') {
      ++log.stats.ignored;
      continue;
    }
    core::Result<CandumpRecord> r = ParseCandumpLine(line);
    if (r.ok()) {
      log.records.push_back(std::move(r).value());
      ++log.stats.records;
    } else {
      ++log.stats.malformed;
      if (log.errors.size() < kMaxErrorsKept) {
        log.errors.push_back("line " + std::to_string(log.stats.lines) + ": " +
                             r.status().message());
      }
    }
  }
  return log;
}

core::Result<CandumpLog> ReadCandumpLog(const std::string& path, int64_t max_bytes) {
  core::Result<std::string> text = core::ReadFileBytes(path, max_bytes);
  if (!text.ok()) return text.status();
  return ParseCandumpLog(*text);
}

core::Status WriteCandumpLog(const std::string& path, const std::vector<CandumpRecord>& records) {
  std::string text;
  text.reserve(records.size() * 48);
  for (const CandumpRecord& r : records) text += FormatCandumpLine(r) + "\n";
  return core::WriteFileAtomically(path, text);
}

}  // namespace fleetmap::drivers::can
