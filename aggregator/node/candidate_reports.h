// A vehicle's reports on the candidates of the current map (the candidate watch,
// docs/architecture.md). CANDIDATES_FREE_<id> names the candidates its scans saw empty:
// they are dropped (Aggregator::DropCandidatesSeenFree). CANDIDATES_HELD_<id> names the
// candidates its beams kept ending at for long enough: they are added
// (Aggregator::ConfirmCandidatesHeld). A report that changes cells makes a journaled version
// of its own, so its MAP_DELTA and the new MAP_CANDIDATES go out; a failed journal write
// changes nothing. A report counts only from the vehicle whose channel it came on and only
// with cells of the current map; anything else is refused, counted and logged once.
// Owns nothing: it changes the current map and sends through the publisher.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "aggregator/aggregator.h"
#include "aggregator/node/map_publisher.h"
#include "aggregator/node/node_reporting.h"
#include "core/result.h"

namespace fleetmap::aggregator::node {

class CandidateReports {
 public:
  // `aggregator` and `publisher` outlive this.
  CandidateReports(Aggregator& aggregator, MapPublisher& publisher, NodeReporting report);
  CandidateReports(const CandidateReports&) = delete;
  CandidateReports& operator=(const CandidateReports&) = delete;

  // The payload of a CANDIDATES_FREE_<id> message on `channel`.
  void OnSeenFree(const std::string& channel, const void* data, int size, double now_s);
  // The payload of a CANDIDATES_HELD_<id> message on `channel`.
  void OnHeld(const std::string& channel, const void* data, int size, double now_s);

 private:
  // Decoded, from the vehicle whose channel it came on; refused (counted, logged) otherwise.
  template <typename Message>
  std::optional<Message> VehicleReport(const std::string& channel, const void* data, int size,
                                       const char* prefix, const std::string& name);
  void Applied(const std::string& vehicle, const core::Result<std::vector<int64_t>>& cells,
               int64_t& counter, const std::string& what, double now_s);

  Aggregator& aggregator_;
  MapPublisher& publisher_;
  NodeReporting report_;
};

}  // namespace fleetmap::aggregator::node
