#include "aggregator/node/map_publisher.h"

#include <algorithm>
#include <chrono>

#include "aggregator/node/candidate_messages.h"
#include "lcmtypes/convert.h"
#include "lcmtypes/transport_convert.h"

namespace fleetmap::aggregator::node {
namespace {

std::vector<int32_t> AllTiles(int32_t count) {
  std::vector<int32_t> all;
  for (int32_t i = 0; i < count; ++i) all.push_back(i);
  return all;
}

}  // namespace

MapPublisher::MapPublisher(const Aggregator& aggregator, const AggregatorNodeOptions& options,
                           Publisher* publisher, NodeReporting report)
    : aggregator_(aggregator),
      options_(options),
      publisher_(publisher),
      report_(report),
      // Sequence numbers follow the wall clock across restarts, whatever time the node
      // is handed (auth/signer.h).
      signer_(options_.fleet_key, options_.process_name,
              auth::FirstSequence(
                  std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
                      .count())) {}

void MapPublisher::SendPendingAck(const MapKey& key, int32_t tile_count,
                                  std::vector<int32_t> received, double now_s) {
  if (!publisher_) return;
  AckFields ack;
  ack.key = key;
  ack.tile_count = tile_count;
  ack.received = std::move(received);
  ack.outcome = fleetmap::tempmap_ack_t::PENDING;
  ack.map_version = aggregator_.store().version();
  Send(Link::kDownlink, lcmtypes::kTempMapAckChannel, AckMessage(ack, lcmtypes::ToUtime(now_s)));
  ++report_.counters.pending_acks_sent;
}

void MapPublisher::SendFinalAck(const MapKey& key, int32_t tile_count, int8_t outcome,
                                const std::string& reason, uint64_t version, double now_s) {
  if (!publisher_) return;
  tile_count = std::clamp(tile_count, 0, options_.assembler.max_tiles);
  AckFields ack;
  ack.key = key;
  ack.tile_count = tile_count;
  ack.received = AllTiles(tile_count);
  ack.outcome = outcome;
  ack.reason = reason;
  ack.map_version = version;
  Send(Link::kDownlink, lcmtypes::kTempMapAckChannel, AckMessage(ack, lcmtypes::ToUtime(now_s)));
}

void MapPublisher::SendMergeReport(const MergeReport& report, const core::Pose2& anchor_in_map,
                                   double map_s) {
  if (!publisher_) return;
  Send(Link::kDownlink, lcmtypes::kMergeReportChannel,
       ReportMessage(report, anchor_in_map, options_.max_report_matches, lcmtypes::ToUtime(map_s)));
  ++report_.counters.merge_reports_sent;
}

void MapPublisher::SendDelta(const MapDelta& delta, double now_s) {
  if (!publisher_) return;
  const auto messages = DeltaMessages(delta, lcmtypes::ToUtime(now_s));
  for (const auto& m : messages) Send(Link::kDownlink, lcmtypes::kMapDeltaChannel, m);
  report_.counters.delta_tiles_sent += static_cast<int64_t>(messages.size());
}

size_t MapPublisher::SendKeyframe(const std::vector<int32_t>* only, double now_s) {
  if (!publisher_) return 0;  // encoding a hundred tiles for nobody
  const auto messages = KeyframeMessages(aggregator_.store(), aggregator_.options().store.tiles,
                                         only, lcmtypes::ToUtime(now_s));
  size_t bytes = 0;
  for (const auto& m : messages) bytes += Send(Link::kDownlink, lcmtypes::kMapKeyframeChannel, m);
  report_.counters.keyframe_tiles_sent += static_cast<int64_t>(messages.size());
  return bytes;
}

size_t MapPublisher::room_bytes() const {
  return publisher_ ? publisher_->RoomBytes(Link::kDownlink) : 0;
}

void MapPublisher::SendCandidates(double now_s) {
  if (!publisher_) return;
  const CurrentMapStore& store = aggregator_.store();
  for (const auto& m :
       CandidateMessages(store.candidates(), store.version(), lcmtypes::ToUtime(now_s)))
    Send(Link::kDownlink, lcmtypes::kMapCandidatesChannel, m);
  ++report_.counters.candidate_sets_sent;
}

void MapPublisher::SendStatus(const StatusFields& fields, double now_s) {
  if (!publisher_) return;
  Send(Link::kDownlink, lcmtypes::StatusChannel(options_.process_name),
       StatusMessage(fields, lcmtypes::ToUtime(now_s)));
}

template <typename T>
size_t MapPublisher::Send(Link link, const std::string& channel, const T& message) {
  if (!publisher_) return 0;
  std::vector<uint8_t> bytes(static_cast<size_t>(message.getEncodedSize()));
  message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  signer_.Seal(channel, bytes);
  if (static_cast<int>(bytes.size()) > options_.max_message_bytes) {
    report_.Refuse("oversize " + channel, report_.counters.oversize_messages,
                   channel + ": a message of " + std::to_string(bytes.size()) +
                       " bytes (more than " + std::to_string(options_.max_message_bytes) +
                       "): one lost packet loses it");
  }
  size_t& largest = largest_[channel];
  largest = std::max(largest, bytes.size());
  if (channel == lcmtypes::kTempMapAckChannel) ++report_.counters.acks_sent;
  report_.counters.bytes_sent += static_cast<int64_t>(bytes.size());
  if (!publisher_->Publish(link, channel, bytes)) {
    report_.Refuse("publish failed", report_.counters.publish_failures,
                   std::string("the ") + LinkName(link) + " refused a message on " + channel);
  }
  return bytes.size();
}

}  // namespace fleetmap::aggregator::node
