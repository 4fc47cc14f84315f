#include "aggregator/node/vehicle_limits.h"

#include <algorithm>
#include <cmath>

namespace fleetmap::aggregator::node {

core::Status VehicleLimitOptions::Validate() const {
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (max_received_bytes < 1024)
    return core::InvalidArgument("limits.max_received_bytes must be >= 1024");
  if (max_pending_maps_per_vehicle < 1)
    return core::InvalidArgument("limits.max_pending_maps_per_vehicle must be >= 1");
  if (!positive(tiles_per_s)) return core::InvalidArgument("limits.tiles_per_s must be > 0");
  if (!(tile_burst >= 1.0)) return core::InvalidArgument("limits.tile_burst must be >= 1");
  if (!positive(merges_per_min)) return core::InvalidArgument("limits.merges_per_min must be > 0");
  if (!(merge_burst >= 1.0)) return core::InvalidArgument("limits.merge_burst must be >= 1");
  if (!(std::isfinite(max_replay_speed) && max_replay_speed >= 1.0))
    return core::InvalidArgument("limits.max_replay_speed must be >= 1");
  if (max_vehicles < 1) return core::InvalidArgument("limits.max_vehicles must be >= 1");
  return core::OkStatus();
}

bool VehicleLimits::Spend(Bucket& b, double elapsed_s, double rate_per_s, double burst) {
  b.tokens = std::min(burst, b.tokens + elapsed_s * rate_per_s);
  if (b.tokens < 1.0) return false;
  b.tokens -= 1.0;
  return true;
}

bool VehicleLimits::Take(Bucket& b, double rate_per_s, double burst, double now_s) {
  // A clock that went back refills nothing; one that jumped ahead fills the bucket once.
  const double elapsed_s = std::max(0.0, now_s - b.last_s);
  b.last_s = now_s;
  return Spend(b, elapsed_s, rate_per_s, burst);
}

bool VehicleLimits::TakeStamped(Bucket& b, double stamp_s, double now_s) const {
  // The stamps' time, but at least the host's (a vehicle whose stamps stall still refills)
  // and at most max_replay_speed times it (forged stamps cannot empty the limit).
  const double host_s = std::max(0.0, now_s - b.last_s);
  const double stamps_s = b.stamped && std::isfinite(stamp_s) ? stamp_s - b.last_stamp_s : 0.0;
  const double elapsed_s = std::clamp(stamps_s, host_s, host_s * options_.max_replay_speed);
  b.last_s = std::max(b.last_s, now_s);
  if (std::isfinite(stamp_s) && (!b.stamped || stamp_s > b.last_stamp_s)) {
    b.last_stamp_s = stamp_s;
    b.stamped = true;
  }
  return Spend(b, elapsed_s, options_.merges_per_min / 60.0, options_.merge_burst);
}

VehicleLimits::Vehicle* VehicleLimits::Find(const std::string& vehicle, double now_s) {
  auto it = vehicles_.find(vehicle);
  if (it != vehicles_.end()) return &it->second;
  if (static_cast<int>(vehicles_.size()) >= options_.max_vehicles) {
    // Forget a vehicle whose buckets are full again: it costs nothing to start it anew.
    const double refill_s = std::max(options_.tile_burst / options_.tiles_per_s,
                                     options_.merge_burst * 60.0 / options_.merges_per_min);
    auto idle = std::find_if(vehicles_.begin(), vehicles_.end(), [&](const auto& v) {
      return now_s - std::max(v.second.tiles.last_s, v.second.merges.last_s) >= refill_s;
    });
    if (idle == vehicles_.end()) return nullptr;
    vehicles_.erase(idle);
  }
  Vehicle v;
  v.tiles = {options_.tile_burst, now_s};
  v.merges = {options_.merge_burst, now_s};
  return &vehicles_.emplace(vehicle, v).first->second;
}

bool VehicleLimits::AllowTile(const std::string& vehicle, double now_s) {
  Vehicle* v = Find(vehicle, now_s);
  return v != nullptr && Take(v->tiles, options_.tiles_per_s, options_.tile_burst, now_s);
}

bool VehicleLimits::AllowMerge(const std::string& vehicle, double map_s, double now_s) {
  Vehicle* v = Find(vehicle, now_s);
  return v != nullptr && TakeStamped(v->merges, map_s, now_s);
}

void VehicleLimits::RefundMerge(const std::string& vehicle) {
  auto it = vehicles_.find(vehicle);
  if (it == vehicles_.end()) return;
  Bucket& b = it->second.merges;
  b.tokens = std::min(options_.merge_burst, b.tokens + 1.0);
}

bool VehicleLimits::FirstThrottle(const std::string& vehicle) {
  if (throttled_.count(vehicle) || static_cast<int>(throttled_.size()) >= options_.max_vehicles)
    return false;
  throttled_[vehicle] = true;
  return true;
}

}  // namespace fleetmap::aggregator::node
