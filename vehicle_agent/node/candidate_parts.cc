#include "vehicle_agent/node/candidate_parts.h"

#include <string>

#include "lcmtypes/channels.h"

namespace fleetmap::vehicle_agent::node {

core::Result<std::optional<std::vector<int64_t>>> CandidateParts::Add(
    const fleetmap::map_candidates_t& part) {
  const bool empty_set = part.parts == 0 && part.part == 0 && part.num_cells == 0;
  if (!empty_set && !(part.parts > 0 && part.part >= 0 && part.part < part.parts))
    return core::InvalidArgument("part " + std::to_string(part.part) + " of " +
                                 std::to_string(part.parts));
  if (part.num_cells < 0 || part.num_cells > lcmtypes::kMaxCandidateCellsPerMessage)
    return core::InvalidArgument("num_cells " + std::to_string(part.num_cells));
  std::vector<int64_t> cells;
  for (int32_t c : part.cells) {
    if (c < 0) return core::InvalidArgument("cell " + std::to_string(c));
    cells.push_back(c);
  }
  if (empty_set) {
    received_.clear();
    utime_ = part.utime;
    return std::optional<std::vector<int64_t>>(std::vector<int64_t>{});
  }
  if (part.utime != utime_ || part.map_version != version_ || part.parts != parts_) {
    received_.clear();
    utime_ = part.utime;
    version_ = part.map_version;
    parts_ = part.parts;
  }
  received_[part.part] = std::move(cells);
  if (static_cast<int>(received_.size()) < parts_) return std::optional<std::vector<int64_t>>();
  std::vector<int64_t> all;
  for (const auto& [index, some] : received_) all.insert(all.end(), some.begin(), some.end());
  received_.clear();
  return std::optional<std::vector<int64_t>>(std::move(all));
}

}  // namespace fleetmap::vehicle_agent::node
