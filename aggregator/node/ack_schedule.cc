#include "aggregator/node/ack_schedule.h"

namespace fleetmap::aggregator::node {

bool AckSchedule::OnTile(const MapKey& key, bool repeated, double now_s) {
  auto [it, inserted] = incomplete_.try_emplace(key);
  Entry& e = it->second;
  if (inserted) e.first_s = now_s;
  e.last_tile_s = now_s;
  e.dirty = true;
  return repeated && (!e.acked || now_s - e.last_ack_s >= interval_s_);
}

void AckSchedule::Restore(const MapKey& key, double now_s) {
  Entry& e = incomplete_[key];
  e.first_s = e.last_tile_s = now_s;
}

std::vector<MapKey> AckSchedule::Due(double now_s) {
  for (auto it = final_acks_.begin(); it != final_acks_.end();) {
    it = now_s - it->second >= interval_s_ ? final_acks_.erase(it) : std::next(it);
  }
  std::vector<MapKey> due;
  for (const auto& [key, e] : incomplete_) {
    const double since = e.acked ? e.last_ack_s : e.first_s;
    if (e.dirty && now_s - since >= interval_s_) due.push_back(key);
  }
  return due;
}

void AckSchedule::Acked(const MapKey& key, double now_s) {
  auto it = incomplete_.find(key);
  if (it == incomplete_.end()) return;
  it->second.acked = true;
  it->second.last_ack_s = now_s;
  it->second.dirty = false;
}

std::vector<MapKey> AckSchedule::Stale(double now_s, double timeout_s) const {
  std::vector<MapKey> stale;
  for (const auto& [key, e] : incomplete_)
    if (now_s - e.last_tile_s >= timeout_s) stale.push_back(key);
  return stale;
}

bool AckSchedule::FinalAckDue(const MapKey& key, double now_s) {
  auto [it, inserted] = final_acks_.try_emplace(key, now_s);
  if (inserted) return true;
  if (now_s - it->second < interval_s_) return false;
  it->second = now_s;
  return true;
}

}  // namespace fleetmap::aggregator::node
