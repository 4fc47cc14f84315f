#include "aggregator/node/candidate_reports.h"

#include "aggregator/node/candidate_messages.h"
#include "aggregator/node/map_key.h"
#include "lcmtypes/convert.h"

namespace fleetmap::aggregator::node {

CandidateReports::CandidateReports(Aggregator& aggregator, MapPublisher& publisher,
                                   NodeReporting report)
    : aggregator_(aggregator), publisher_(publisher), report_(report) {}

template <typename Message>
std::optional<Message> CandidateReports::VehicleReport(const std::string& channel, const void* data,
                                                       int size, const char* prefix,
                                                       const std::string& name) {
  auto msg = lcmtypes::Decode<Message>(data, size);
  if (!msg.ok()) {
    report_.Refuse(name + ": malformed", report_.counters.malformed_messages,
                   channel + ": not a " + Message::getTypeName() + ": " + msg.status().ToString());
    return std::nullopt;
  }
  if (msg->vehicle_id != lcmtypes::ChannelSuffix(channel, prefix)) {
    report_.Refuse(name + ": wrong vehicle id", report_.counters.wrong_vehicle_id,
                   channel + ": a report of vehicle '" +
                       msg->vehicle_id.substr(0, kMaxUplinkVehicleIdBytes) +
                       "' refused: a vehicle reports on its own channel");
    return std::nullopt;
  }
  return std::move(*msg);
}

void CandidateReports::OnSeenFree(const std::string& channel, const void* data, int size,
                                  double now_s) {
  const auto msg = VehicleReport<fleetmap::candidates_free_t>(
      channel, data, size, lcmtypes::kCandidatesFreePrefix, "CANDIDATES_FREE");
  if (!msg) return;
  auto report = SeenFreeFromMessage(*msg, aggregator_.store().current_map().geometry().num_cells());
  if (!report.ok())
    return report_.Refuse("CANDIDATES_FREE: invalid", report_.counters.bad_seen_free,
                          channel + ": report refused: " + report.status().ToString());
  ++report_.counters.seen_free_reports;
  Applied(msg->vehicle_id, aggregator_.DropCandidatesSeenFree(msg->vehicle_id, *report, now_s),
          report_.counters.candidates_dropped, "saw free not dropped", now_s);
}

void CandidateReports::OnHeld(const std::string& channel, const void* data, int size,
                              double now_s) {
  const auto msg = VehicleReport<fleetmap::candidates_held_t>(
      channel, data, size, lcmtypes::kCandidatesHeldPrefix, "CANDIDATES_HELD");
  if (!msg) return;
  auto report = HeldFromMessage(*msg, aggregator_.store().current_map().geometry().num_cells());
  if (!report.ok())
    return report_.Refuse("CANDIDATES_HELD: invalid", report_.counters.bad_held,
                          channel + ": report refused: " + report.status().ToString());
  ++report_.counters.held_reports;
  Applied(msg->vehicle_id, aggregator_.ConfirmCandidatesHeld(msg->vehicle_id, *report, now_s),
          report_.counters.candidates_held_added, "saw held not added", now_s);
}

// The cells a vehicle's report changed, in a version of their own: counted, and their delta
// and the new set of candidates go out. A failed journal write changed nothing.
void CandidateReports::Applied(const std::string& vehicle,
                               const core::Result<std::vector<int64_t>>& cells, int64_t& counter,
                               const std::string& what, double now_s) {
  if (!cells.ok()) {
    ++report_.counters.persist_errors;
    report_.log.Warning("candidates " + vehicle.substr(0, kMaxUplinkVehicleIdBytes) + " " + what +
                        ": " + cells.status().ToString());
    return;
  }
  if (cells->empty()) return;
  counter += static_cast<int64_t>(cells->size());
  const CurrentMapStore& store = aggregator_.store();
  if (auto delta = store.Delta(store.version() - 1); delta.ok())
    publisher_.SendDelta(*delta, now_s);
  publisher_.SendCandidates(now_s);
}

}  // namespace fleetmap::aggregator::node
