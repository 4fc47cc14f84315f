#include "vehicle_agent/node/agent_counters.h"

namespace fleetmap::vehicle_agent::node {

NamedCounters CollectCounters(const AgentNodeCounters& c, const InputQueue& queue,
                              const OutboxCounters& o, const MapFollowerCounters& m,
                              const LocalizerCounters& l) {
  return {
      {"scans", c.scans},
      {"scans_skipped", queue.scans_skipped()},
      {"scans_waiting_for_map", c.scans_waiting_for_map},
      {"scans_waiting_for_pose", c.scans_waiting_for_pose},
      {"odometry", c.odometry},
      {"external_poses", c.external_poses},
      {"tempmaps_closed", c.tempmaps_closed},
      {"tempmaps_dropped", o.maps_dropped},
      {"tiles_sent", o.tiles_sent},
      {"tiles_resent", o.tiles_resent},
      {"acks", c.acks},
      {"auth_refused", c.auth_refused},
      {"seen_free_reports", c.seen_free_reports},
      {"held_reports", c.held_reports},
      {"maps_merged", c.maps_merged},
      {"maps_rejected", c.maps_rejected},
      {"maps_duplicate", c.maps_duplicate},
      {"map_versions_applied", m.versions_applied},
      {"keyframe_requests", m.requests},
      {"keyframe_tiles", m.keyframe_tiles},
      {"delta_tiles", m.delta_tiles},
      {"map_tiles_stale", m.stale_tiles},
      {"map_tiles_refused", m.refused_tiles},
      {"map_tiles_wrong_geometry", m.wrong_geometry_tiles},
      {"map_resets", m.resets},
      {"map_swaps_failed", c.map_swaps_failed},
      {"messages", c.messages},
      {"malformed_messages", c.malformed_messages},
      {"wrong_vehicle_messages", c.wrong_vehicle},
      {"inputs_dropped", queue.inputs_dropped()},
      {"beams_invalid", l.beams_invalid},
      {"scans_invalid", l.scans_invalid},
      {"scans_out_of_order", l.scans_out_of_order},
      {"odometry_invalid", l.odometry_invalid},
      {"odometry_out_of_order", l.odometry_out_of_order},
      {"odometry_jumps", l.odometry_jumps},
      {"clock_steps_back", l.clock_steps_back},
      {"external_poses_dropped", l.external_poses_dropped},
      {"global_searches", l.global_searches},
      {"starts_from_last_pose", c.starts_from_last_pose},
      {"lost", c.lost},
      {"lost_searches", l.lost_searches},
      {"relocalizations", l.relocalizations},
      {"tempmaps_dropped_lost", c.tempmaps_dropped_lost},
      {"persist_errors", o.persist_errors},
      {"tempmaps_resent_after_recovery", o.maps_resent_after_recovery},
      {"publish_failures", c.publish_failures},
  };
}

int64_t CounterValue(const NamedCounters& counters, const std::string& name) {
  for (const auto& [n, v] : counters)
    if (n == name) return v;
  return -1;
}

}  // namespace fleetmap::vehicle_agent::node
