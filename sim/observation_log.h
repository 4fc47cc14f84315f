// What the fleet's scanners could have seen of the changes, recorded by the simulator from
// its noise-free beams: for every cell of every semi-static object, when a beam last hit it
// and when a beam last passed through it; for every object, when each vehicle first saw its
// appearance or disappearance. The evaluation scores a map against this, so that a change
// no scanner ever saw is not held against the system.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "core/map/log_odds.h"

namespace fleetmap::sim {

constexpr double kNever = std::numeric_limits<double>::quiet_NaN();

struct CellObservations {
  double last_hit_s = kNever;
  double last_pass_s = kNever;  // a beam went through the cell: it was free then
  bool ever_hit = false;
  // The last observed state: occupied if hit last, free if passed last, unknown if never.
  core::CellState LastState() const;
};

struct ObjectChangeSeen {
  double appear_seen_s = kNever;     // first hit at or after appear_s (per vehicle)
  double disappear_seen_s = kNever;  // first pass through at or after disappear_s
};

class ObservationLog {
 public:
  // `raster`: World::object_raster(), each cell's object (1-based) or 0; read here only.
  ObservationLog(size_t num_objects, size_t num_vehicles, const std::vector<int32_t>* raster);

  void RecordHit(int64_t cell, double t_s);
  void RecordPass(int64_t cell, double t_s);
  // Called by the simulator with the object's index when vehicle `v` saw its change.
  void RecordAppearSeen(size_t object, size_t vehicle, double t_s);
  void RecordDisappearSeen(size_t object, size_t vehicle, double t_s);

  // Observations of a cell inside an object, or nullptr for cells of no object.
  const CellObservations* Cell(int64_t cell) const;
  const ObjectChangeSeen& Seen(size_t object, size_t vehicle) const {
    return seen_[object * num_vehicles_ + vehicle];
  }
  size_t num_vehicles() const { return num_vehicles_; }

 private:
  std::vector<int32_t> slot_of_cell_;  // index into cells_, -1 for cells of no object
  std::vector<CellObservations> cells_;
  size_t num_vehicles_;
  std::vector<ObjectChangeSeen> seen_;
};

}  // namespace fleetmap::sim
