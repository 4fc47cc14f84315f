#include "vehicle_agent/node/agent_sender.h"

#include <chrono>

#include "lcmtypes/channels.h"
#include "lcmtypes/convert.h"
#include "lcmtypes/transport_convert.h"
#include "vehicle_agent/node/agent_messages.h"

namespace fleetmap::vehicle_agent::node {

AgentSender::AgentSender(const AgentNodeOptions& options, Publisher* publisher, CauseLog* log,
                         AgentNodeCounters* counters)
    : vehicle_id_(options.pipeline.vehicle_id),
      software_version_(options.software_version),
      pose_link_(options.pose_link),
      utime_offset_s_(options.utime_offset_s),
      publisher_(publisher),
      log_(log),
      counters_(counters),
      // Sequence numbers follow the wall clock across restarts (auth/signer.h).
      signer_(options.fleet_key, options.pipeline.vehicle_id,
              auth::FirstSequence(
                  std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
                      .count())) {}

int64_t AgentSender::Utime(double now_s) const {
  return lcmtypes::ToUtime(now_s + utime_offset_s_);
}

template <typename T>
void AgentSender::Send(Link link, const std::string& channel, const T& message) {
  std::vector<uint8_t> bytes = Encode(message);
  signer_.Seal(channel, bytes);
  if (!publisher_->Publish(link, channel, bytes)) {
    ++counters_->publish_failures;
    log_->Once("publish " + channel, "cannot publish on " + channel + " (" + LinkName(link) + ")");
  }
}

void AgentSender::SendStep(const core::LaserScan& scan, const AgentStep& step,
                           int32_t tempmap_sequence) {
  Send(pose_link_, lcmtypes::PoseChannel(vehicle_id_), lcmtypes::ToMessage(step.pose, vehicle_id_));
  Send(pose_link_, lcmtypes::DivergenceChannel(vehicle_id_),
       DivergenceMessage(vehicle_id_, scan.stamp_s, step, tempmap_sequence));
}

void AgentSender::SendTiles(const std::vector<core::TempMapTile>& tiles, double now_s) {
  const std::string channel = lcmtypes::TempMapChannel(vehicle_id_);
  for (const core::TempMapTile& tile : tiles)
    Send(Link::kUplink, channel, lcmtypes::ToMessage(tile, Utime(now_s)));
}

void AgentSender::SendMapRequest(int32_t have_version, const std::vector<int32_t>& tiles,
                                 double now_s) {
  Send(Link::kUplink, lcmtypes::kMapRequestChannel,
       MapRequestMessage(vehicle_id_, have_version, tiles, Utime(now_s)));
}

void AgentSender::SendCandidates(const CandidatesSeenFree& seen, const CandidatesHeld& held,
                                 int32_t map_version, double now_s) {
  const std::string free_channel = lcmtypes::CandidatesFreeChannel(vehicle_id_);
  for (const auto& m : SeenFreeMessages(vehicle_id_, map_version, seen, Utime(now_s))) {
    Send(Link::kUplink, free_channel, m);
    ++counters_->seen_free_reports;
  }
  const std::string held_channel = lcmtypes::CandidatesHeldChannel(vehicle_id_);
  for (const auto& m : HeldMessages(vehicle_id_, map_version, held, Utime(now_s))) {
    Send(Link::kUplink, held_channel, m);
    ++counters_->held_reports;
  }
}

void AgentSender::SendStatus(int32_t map_version, const std::string& state,
                             const NamedCounters& counters, bool authenticated, double now_s) {
  const std::string process = "agent_" + vehicle_id_;
  fleetmap::status_t status =
      StatusMessage(process, software_version_, map_version, state, counters, Utime(now_s));
  status.authenticated = authenticated;
  Send(Link::kUplink, lcmtypes::StatusChannel(process), status);
}

}  // namespace fleetmap::vehicle_agent::node
