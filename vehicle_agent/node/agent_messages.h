// The messages the agent builds itself (the others come from lcmtypes' conversions), and
// the encoding of any message into the bytes a Publisher sends.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "fleetmap/candidates_free_t.hpp"
#include "fleetmap/candidates_held_t.hpp"
#include "fleetmap/divergence_t.hpp"
#include "fleetmap/map_request_t.hpp"
#include "fleetmap/status_t.hpp"
#include "vehicle_agent/agent_pipeline.h"
#include "vehicle_agent/node/agent_counters.h"

namespace fleetmap::vehicle_agent::node {

// DIVERGENCE_<id>: the paper's Fig. 3 sample of one scan, stamped with the scan's time.
fleetmap::divergence_t DivergenceMessage(const std::string& vehicle_id, double scan_stamp_s,
                                         const AgentStep& step, int32_t tempmap_sequence);
// MAP_REQUEST for the whole map (or the deltas since have_version, -1: none held).
fleetmap::map_request_t MapRequestMessage(const std::string& vehicle_id, int32_t have_version,
                                          const std::vector<int32_t>& tiles, int64_t utime);
// CANDIDATES_FREE_<id>: the candidates seen free in messages of at most
// kMaxCandidateCellsPerMessage cells, the passes' times as scan time (as maps carry it).
std::vector<fleetmap::candidates_free_t> SeenFreeMessages(const std::string& vehicle_id,
                                                          int32_t map_version,
                                                          const CandidatesSeenFree& seen,
                                                          int64_t utime);
// CANDIDATES_HELD_<id>: the held candidates in messages of at most kMaxHeldCellsPerMessage
// cells, times as milliseconds after the earliest hold's start.
std::vector<fleetmap::candidates_held_t> HeldMessages(const std::string& vehicle_id,
                                                      int32_t map_version,
                                                      const CandidatesHeld& held, int64_t utime);
fleetmap::status_t StatusMessage(const std::string& process, const std::string& software_version,
                                 int32_t map_version, const std::string& state,
                                 const NamedCounters& counters, int64_t utime);

template <typename T>
std::vector<uint8_t> Encode(const T& message) {
  std::vector<uint8_t> bytes(static_cast<size_t>(message.getEncodedSize()));
  message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

}  // namespace fleetmap::vehicle_agent::node
