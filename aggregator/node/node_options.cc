#include "aggregator/node/node_options.h"

#include <algorithm>
#include <cmath>

namespace fleetmap::aggregator::node {
namespace {

bool Positive(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace

core::Status AggregatorNodeOptions::Validate() const {
  if (!Positive(pending_ack_interval_s))
    return core::InvalidArgument("node.pending_ack_interval_s must be > 0");
  if (!Positive(downlink_bytes_per_s))
    return core::InvalidArgument("node.downlink_bytes_per_s must be > 0");
  if (!Positive(downlink_messages_per_s))
    return core::InvalidArgument("node.downlink_messages_per_s must be > 0");
  if (!(keyframe_share > 0.0 && keyframe_share <= 1.0))
    return core::InvalidArgument("node.keyframe_share must be > 0 and <= 1");
  if (!(std::isfinite(keyframe_period_s) && keyframe_period_s >= 0.0))
    return core::InvalidArgument("node.keyframe_period_s must be >= 0");
  if (!Positive(status_period_s)) return core::InvalidArgument("node.status_period_s must be > 0");
  if (!(std::isfinite(recovery_request_s) && recovery_request_s >= 0.0))
    return core::InvalidArgument("node.recovery_request_s must be >= 0");
  if (!Positive(pending_map_timeout_s))
    return core::InvalidArgument("node.pending_map_timeout_s must be > 0");
  if (max_message_bytes < 1024)
    return core::InvalidArgument("node.max_message_bytes must be >= 1024");
  if (max_report_matches < 0) return core::InvalidArgument("node.max_report_matches must be >= 0");
  if (max_remembered_rejections < 1)
    return core::InvalidArgument("node.max_remembered_rejections must be >= 1");
  if (max_retry_maps < 1) return core::InvalidArgument("node.max_retry_maps must be >= 1");
  if (max_held_maps < 1) return core::InvalidArgument("node.max_held_maps must be >= 1");
  if (process_name.empty() || process_name.size() > 64)
    return core::InvalidArgument("node.process_name must have 1 to 64 characters");
  // Acknowledgements list tile indices as int16 (tempmap_ack_t).
  if (assembler.max_tiles > 32767)
    return core::InvalidArgument("assembler.max_tiles must be <= 32767");
  FLEETMAP_RETURN_IF_ERROR(limits.Validate());
  return assembler.Validate().WithContext("assembler");
}

core::PacerOptions AggregatorNodeOptions::DownlinkPacer() const {
  core::PacerOptions pacer;
  pacer.rate_per_s = downlink_messages_per_s;
  pacer.burst = std::max(1.0, downlink_messages_per_s * 0.1);
  pacer.bytes_per_s = downlink_bytes_per_s;
  pacer.burst_bytes = std::max<double>(max_message_bytes, downlink_bytes_per_s * 0.1);
  return pacer;
}

}  // namespace fleetmap::aggregator::node
