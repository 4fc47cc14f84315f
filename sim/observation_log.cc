#include "sim/observation_log.h"

#include <cmath>

namespace fleetmap::sim {

core::CellState CellObservations::LastState() const {
  const bool hit = !std::isnan(last_hit_s), pass = !std::isnan(last_pass_s);
  if (!hit && !pass) return core::CellState::kUnknown;
  if (hit && (!pass || last_hit_s >= last_pass_s)) return core::CellState::kOccupied;
  return core::CellState::kFree;
}

ObservationLog::ObservationLog(size_t num_objects, size_t num_vehicles,
                               const std::vector<int32_t>* raster)
    : slot_of_cell_(raster->size(), -1),
      num_vehicles_(num_vehicles),
      seen_(num_objects * num_vehicles) {
  for (size_t i = 0; i < raster->size(); ++i) {
    if ((*raster)[i] == 0) continue;
    slot_of_cell_[i] = static_cast<int32_t>(cells_.size());
    cells_.emplace_back();
  }
}

void ObservationLog::RecordHit(int64_t cell, double t_s) {
  const int32_t slot = slot_of_cell_[cell];
  if (slot < 0) return;
  cells_[slot].last_hit_s = t_s;
  cells_[slot].ever_hit = true;
}

void ObservationLog::RecordPass(int64_t cell, double t_s) {
  const int32_t slot = slot_of_cell_[cell];
  if (slot >= 0) cells_[slot].last_pass_s = t_s;
}

void ObservationLog::RecordAppearSeen(size_t object, size_t vehicle, double t_s) {
  double& seen = seen_[object * num_vehicles_ + vehicle].appear_seen_s;
  if (std::isnan(seen)) seen = t_s;
}

void ObservationLog::RecordDisappearSeen(size_t object, size_t vehicle, double t_s) {
  double& seen = seen_[object * num_vehicles_ + vehicle].disappear_seen_s;
  if (std::isnan(seen)) seen = t_s;
}

const CellObservations* ObservationLog::Cell(int64_t cell) const {
  const int32_t slot = slot_of_cell_[cell];
  return slot < 0 ? nullptr : &cells_[slot];
}

}  // namespace fleetmap::sim
