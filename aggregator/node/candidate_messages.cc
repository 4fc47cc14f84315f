#include "aggregator/node/candidate_messages.h"

#include <cmath>
#include <limits>
#include <string>

#include "lcmtypes/channels.h"
#include "lcmtypes/convert.h"

namespace fleetmap::aggregator::node {

std::vector<fleetmap::map_candidates_t> CandidateMessages(
    const std::map<int64_t, Candidate>& candidates, uint64_t version, int64_t utime) {
  constexpr size_t kPerPart = lcmtypes::kMaxCandidateCellsPerMessage;
  const size_t parts = (candidates.size() + kPerPart - 1) / kPerPart;
  std::vector<fleetmap::map_candidates_t> out;
  fleetmap::map_candidates_t m;
  m.utime = utime;
  m.map_version = static_cast<int32_t>(std::min<uint64_t>(version, INT32_MAX));
  m.parts = static_cast<int16_t>(std::min<size_t>(parts, INT16_MAX));
  m.part = 0;
  m.num_cells = 0;
  if (parts == 0) {
    out.push_back(m);
    return out;
  }
  for (const auto& [cell, candidate] : candidates) {
    if (cell > std::numeric_limits<int32_t>::max()) break;  // no map is that large
    m.cells.push_back(static_cast<int32_t>(cell));
    if (m.cells.size() == kPerPart) {
      m.num_cells = static_cast<int32_t>(m.cells.size());
      out.push_back(m);
      m.cells.clear();
      if (++m.part == m.parts) break;  // more than INT16_MAX parts: the rest is not sent
    }
  }
  if (!m.cells.empty()) {
    m.num_cells = static_cast<int32_t>(m.cells.size());
    out.push_back(m);
  }
  return out;
}

namespace {

core::Status CheckCount(int32_t count, int max) {
  if (count >= 1 && count <= max) return core::OkStatus();
  return core::InvalidArgument("num_cells " + std::to_string(count) + " (1 to " +
                               std::to_string(max) + ")");
}

core::Status CheckCell(int32_t cell, int64_t num_cells) {
  if (cell >= 0 && cell < num_cells) return core::OkStatus();
  return core::InvalidArgument("cell " + std::to_string(cell) + " outside the map's " +
                               std::to_string(num_cells) + " cells");
}

}  // namespace

core::Result<SeenFreeReport> SeenFreeFromMessage(const fleetmap::candidates_free_t& message,
                                                 int64_t num_cells) {
  FLEETMAP_RETURN_IF_ERROR(CheckCount(message.num_cells, lcmtypes::kMaxCandidateCellsPerMessage));
  SeenFreeReport report;
  report.first_pass_s = lcmtypes::FromUtime(message.first_pass_utime);
  report.last_pass_s = lcmtypes::FromUtime(message.last_pass_utime);
  if (!(report.first_pass_s <= report.last_pass_s))
    return core::InvalidArgument("first_pass_utime after last_pass_utime");
  for (int32_t cell : message.cells) {
    FLEETMAP_RETURN_IF_ERROR(CheckCell(cell, num_cells));
    report.cells.push_back(cell);
  }
  return report;
}

core::Result<HeldReport> HeldFromMessage(const fleetmap::candidates_held_t& message,
                                         int64_t num_cells) {
  FLEETMAP_RETURN_IF_ERROR(CheckCount(message.num_cells, lcmtypes::kMaxHeldCellsPerMessage));
  HeldReport report;
  const double base_s = lcmtypes::FromUtime(message.base_utime);
  for (int32_t i = 0; i < message.num_cells; ++i) {
    const int32_t cell = message.cells[static_cast<size_t>(i)];
    FLEETMAP_RETURN_IF_ERROR(CheckCell(cell, num_cells));
    const int32_t since = message.since_ms[static_cast<size_t>(i)];
    const int32_t until = message.until_ms[static_cast<size_t>(i)];
    if (since > until)
      return core::InvalidArgument("cell " + std::to_string(cell) + " held until before since");
    report.cells.push_back(cell);
    report.since_s.push_back(base_s + 1e-3 * since);
    report.until_s.push_back(base_s + 1e-3 * until);
  }
  return report;
}

}  // namespace fleetmap::aggregator::node
