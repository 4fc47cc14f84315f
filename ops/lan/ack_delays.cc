#include "ops/lan/ack_delays.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>

#include "auth/trailer.h"
#include "fleetmap/tempmap_ack_t.hpp"
#include "fleetmap/tempmap_tile_t.hpp"
#include "lcmtypes/channels.h"
#include "lcmtypes/convert.h"

namespace fleetmap::ops::lan {
namespace {

template <typename T>
core::Result<T> Payload(const LogMessage& m) {
  return lcmtypes::Decode<T>(m.data.data(), int(auth::PayloadSize(m.data.data(), m.data.size())));
}

// The nearest-rank percentile of sorted values.
double Percentile(const std::vector<double>& sorted, double p) {
  const size_t rank = static_cast<size_t>(std::ceil(p * static_cast<double>(sorted.size())));
  return sorted[std::min(sorted.size() - 1, rank == 0 ? 0 : rank - 1)];
}

std::string Line(const std::string& name, double value, const char* unit) {
  char text[160];
  std::snprintf(text, sizeof(text), "%s %.6g %s\n", name.c_str(), value, unit);
  return text;
}

}  // namespace

AckDelays MeasureAckDelays(const std::vector<LogMessage>& messages) {
  AckDelays out;
  std::map<std::pair<std::string, int32_t>, int64_t> last_tile_utime;
  for (const LogMessage& m : messages) {
    if (m.channel == lcmtypes::kTempMapAckChannel) {
      auto ack = Payload<fleetmap::tempmap_ack_t>(m);
      if (!ack.ok() || ack->outcome == fleetmap::tempmap_ack_t::PENDING) continue;
      const auto tile = last_tile_utime.find({ack->vehicle_id, ack->tempmap_seq});
      if (tile == last_tile_utime.end()) {
        ++out.untimed;
        continue;
      }
      out.delays_s.push_back(static_cast<double>(m.recv_utime - tile->second) * 1e-6);
      last_tile_utime.erase(tile);  // a resend's DUPLICATE is timed from its own tiles
    } else if (lcmtypes::HasPrefix(m.channel, lcmtypes::kTempMapPrefix)) {
      auto tile = Payload<fleetmap::tempmap_tile_t>(m);
      if (tile.ok()) last_tile_utime[{tile->vehicle_id, tile->tempmap_seq}] = m.recv_utime;
    }
  }
  return out;
}

std::string AckDelayFigureLines(const AckDelays& delays) {
  std::string out = Line("acks.count", static_cast<double>(delays.delays_s.size()), "count");
  out += Line("acks.untimed", delays.untimed, "count");
  if (delays.delays_s.empty()) return out;
  std::vector<double> sorted = delays.delays_s;
  std::sort(sorted.begin(), sorted.end());
  out += Line("acks.delay_s.median", Percentile(sorted, 0.5), "s");
  out += Line("acks.delay_s.p95", Percentile(sorted, 0.95), "s");
  out += Line("acks.delay_s.max", sorted.back(), "s");
  return out;
}

}  // namespace fleetmap::ops::lan
