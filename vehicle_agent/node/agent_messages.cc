#include "vehicle_agent/node/agent_messages.h"

#include <algorithm>
#include <cmath>

#include "lcmtypes/channels.h"
#include "lcmtypes/convert.h"

namespace fleetmap::vehicle_agent::node {

fleetmap::divergence_t DivergenceMessage(const std::string& vehicle_id, double scan_stamp_s,
                                         const AgentStep& step, int32_t tempmap_sequence) {
  fleetmap::divergence_t d;
  d.utime = lcmtypes::ToUtime(scan_stamp_s);
  d.vehicle_id = vehicle_id;
  d.w_avg = step.divergence.w_avg;
  d.w_slow = step.divergence.w_slow;
  d.w_fast = step.divergence.w_fast;
  d.d = step.divergence.d;
  d.state = step.building ? fleetmap::divergence_t::BUILDING : fleetmap::divergence_t::FREE;
  d.rotating = step.divergence.rotating;
  d.tempmap_seq = tempmap_sequence;
  return d;
}

fleetmap::map_request_t MapRequestMessage(const std::string& vehicle_id, int32_t have_version,
                                          const std::vector<int32_t>& tiles, int64_t utime) {
  fleetmap::map_request_t r;
  r.utime = utime;
  r.vehicle_id = vehicle_id;
  r.have_version = have_version;
  // No tile list: the whole map, or the deltas since have_version.
  r.num_tiles = static_cast<int32_t>(tiles.size());
  r.tiles = tiles;
  return r;
}

std::vector<fleetmap::candidates_free_t> SeenFreeMessages(const std::string& vehicle_id,
                                                          int32_t map_version,
                                                          const CandidatesSeenFree& seen,
                                                          int64_t utime) {
  std::vector<fleetmap::candidates_free_t> out;
  fleetmap::candidates_free_t m;
  m.utime = utime;
  m.vehicle_id = vehicle_id;
  m.map_version = map_version;
  m.first_pass_utime = lcmtypes::ToUtime(seen.first_pass_s);
  m.last_pass_utime = lcmtypes::ToUtime(seen.last_pass_s);
  for (size_t begin = 0; begin < seen.cells.size();
       begin += lcmtypes::kMaxCandidateCellsPerMessage) {
    const size_t end =
        std::min(seen.cells.size(), begin + size_t{lcmtypes::kMaxCandidateCellsPerMessage});
    m.cells.assign(seen.cells.begin() + static_cast<std::ptrdiff_t>(begin),
                   seen.cells.begin() + static_cast<std::ptrdiff_t>(end));
    m.num_cells = static_cast<int32_t>(m.cells.size());
    out.push_back(m);
  }
  return out;
}

std::vector<fleetmap::candidates_held_t> HeldMessages(const std::string& vehicle_id,
                                                      int32_t map_version,
                                                      const CandidatesHeld& held, int64_t utime) {
  std::vector<fleetmap::candidates_held_t> out;
  const size_t n = std::min({held.cells.size(), held.since_s.size(), held.until_s.size()});
  if (n == 0) return out;
  const double base_s = *std::min_element(held.since_s.begin(), held.since_s.begin() + n);
  auto ms = [&](double t_s) { return static_cast<int32_t>(std::lround((t_s - base_s) * 1e3)); };
  fleetmap::candidates_held_t m;
  m.utime = utime;
  m.vehicle_id = vehicle_id;
  m.map_version = map_version;
  m.base_utime = lcmtypes::ToUtime(base_s);  // scan time, as maps carry it
  for (size_t begin = 0; begin < n; begin += lcmtypes::kMaxHeldCellsPerMessage) {
    const size_t end = std::min(n, begin + size_t{lcmtypes::kMaxHeldCellsPerMessage});
    m.cells.clear(), m.since_ms.clear(), m.until_ms.clear();
    for (size_t i = begin; i < end; ++i) {
      m.cells.push_back(static_cast<int32_t>(held.cells[i]));
      m.since_ms.push_back(ms(held.since_s[i]));
      m.until_ms.push_back(ms(held.until_s[i]));
    }
    m.num_cells = static_cast<int32_t>(m.cells.size());
    out.push_back(m);
  }
  return out;
}

fleetmap::status_t StatusMessage(const std::string& process, const std::string& software_version,
                                 int32_t map_version, const std::string& state,
                                 const NamedCounters& counters, int64_t utime) {
  fleetmap::status_t s;
  s.utime = utime;
  s.process = process;
  s.software_version = software_version;
  s.map_version = map_version;
  s.state = state;
  s.authenticated = false;
  for (const auto& [name, value] : counters) {
    s.counter_names.push_back(name);
    s.counter_values.push_back(value);
  }
  s.num_counters = static_cast<int32_t>(s.counter_names.size());
  return s;
}

}  // namespace fleetmap::vehicle_agent::node
