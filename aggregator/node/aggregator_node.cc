#include "aggregator/node/aggregator_node.h"

#include "aggregator/node/map_hash.h"
#include "aggregator/node/messages.h"
#include "lcmtypes/channels.h"

namespace fleetmap::aggregator::node {

core::Result<std::unique_ptr<AggregatorNode>> AggregatorNode::Create(Aggregator aggregator,
                                                                     AggregatorNodeOptions options,
                                                                     Publisher* publisher,
                                                                     LogSink log, double now_s) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  TileSpool spool;
  if (!options.spool_dir.empty())
    FLEETMAP_ASSIGN_OR_RETURN(spool, TileSpool::Open(options.spool_dir));
  std::unique_ptr<AggregatorNode> node(new AggregatorNode(std::move(aggregator), std::move(options),
                                                          std::move(spool), publisher,
                                                          std::move(log), now_s));
  node->receiver_.RestoreSpool(now_s);
  return node;
}

AggregatorNode::AggregatorNode(Aggregator aggregator, AggregatorNodeOptions options,
                               TileSpool spool, Publisher* publisher, LogSink log, double now_s)
    : options_(std::move(options)),
      aggregator_(std::move(aggregator)),
      log_(std::move(log)),
      spool_(std::move(spool)),
      limits_(options_.limits),
      gate_(options_, {counters_, log_}),
      publisher_(aggregator_, options_, publisher, {counters_, log_}),
      committer_(aggregator_, options_, spool_, limits_, publisher_, {counters_, log_}),
      candidate_reports_(aggregator_, publisher_, {counters_, log_}),
      answerer_(aggregator_, options_, publisher_, {counters_, log_}, now_s),
      receiver_(options_, spool_, limits_, committer_, publisher_, {counters_, log_}),
      next_status_s_(now_s) {}

void AggregatorNode::OnMessage(const std::string& channel, const void* data, int size,
                               double now_s) {
  const std::optional<UplinkMessage> message = gate_.Open(channel, data, size);
  if (!message) return;
  switch (message->kind) {
    case UplinkKind::kTempMapTile:
      receiver_.OnTile(channel, message->data, message->size, now_s);
      break;
    case UplinkKind::kCandidatesFree:
      candidate_reports_.OnSeenFree(channel, message->data, message->size, now_s);
      break;
    case UplinkKind::kCandidatesHeld:
      candidate_reports_.OnHeld(channel, message->data, message->size, now_s);
      break;
    case UplinkKind::kMapRequest:
      answerer_.OnRequest(message->data, message->size);
      break;
  }
}

// The committer first, so that a map merged now is in the version that the acknowledgements,
// answers and STATUS sent after it name.
void AggregatorNode::Tick(double now_s) {
  committer_.Tick(now_s);
  receiver_.Tick(now_s);
  answerer_.Tick(now_s);
  if (now_s >= next_status_s_) {
    SendStatus(now_s);
    next_status_s_ = now_s + options_.status_period_s;
  }
}

void AggregatorNode::SendStatus(double now_s) {
  if (!publisher_.enabled()) return;
  StatusFields s;
  s.process = options_.process_name;
  s.software_version = options_.software_version;
  s.map_version = aggregator_.store().version();
  s.state = state();
  s.authenticated = authenticated();
  s.counters = Named(counters_);
  s.counters.emplace_back("incomplete_maps", static_cast<int64_t>(incomplete_maps()));
  s.counters.emplace_back("throttled_vehicles", limits_.throttled_vehicles());
  for (const auto& named : auth::Named(auth_counters())) s.counters.push_back(named);
  if (options_.recovery.id != 0 && now_s < options_.recovery.until_s) {
    s.counters.emplace_back(lcmtypes::kRecoveryIdCounter, options_.recovery.id);
    s.counters.emplace_back(lcmtypes::kRecoveredVersionCounter, options_.recovery.version);
  }
  publisher_.SendStatus(s, now_s);
}

std::string AggregatorNode::FinalLine() const {
  return node::FinalLine(aggregator_.store().version(), MapHash(aggregator_.store().current_map()),
                         counters_.maps_merged, counters_.maps_rejected);
}

}  // namespace fleetmap::aggregator::node
