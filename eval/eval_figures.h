// The evaluation's pictures, as PNG: the current map against the truth (the paper's Fig. 5,
// coloured by correct, missed and false cells), the divergence trace (the paper's Fig. 3) and
// the vehicles' paths.
#pragma once

#include <string>

#include "eval/evaluator.h"

namespace fleetmap::eval {

// What the overlay knows of one cell.
struct OverlayCell {
  bool is_static = false;       // occupied in the static map
  bool occupied = false;        // occupied in the final map
  bool ever_occupied = false;   // occupied in the current map at some time of the run
  bool true_added = false;      // truly occupied at the end and not static (an object)
  bool true_removed = false;    // seen occupied by a scanner, truly free at the end
  bool actor_swept = false;     // a person's or forklift's disc covered it at some time
  bool seen_free_near = false;  // a candidate within a cell was dropped as seen free
};
enum class OverlayClass {
  kNone,
  kAddedOk,
  kFalseAdded,
  kMissed,
  kMissedSeenFree,  // missed where a vehicle reported a candidate free
  kRemovedOk,
  kFalseRemoval,
  kMissedRemoval,
  kWallErased,
  kActorMapped,
};
// One class per cell. An actor's cell that was mapped at any time, whether still in the final
// map or removed again, is kActorMapped (never a false addition or a false removal).
OverlayClass ClassifyOverlayCell(const OverlayCell& c);

// Grey map; green: correct added, red: false added, blue: missed added (white where a
// candidate there was dropped as seen free); cyan: correct removed,
// magenta: false removed, orange: missed removed; yellow: static cells erased; purple: actor
// cells mapped at any time.
core::Status WriteOverlayPng(const sim::World& world, const sim::ObservationLog& observations,
                             const RunRecord& run, const std::string& path);
// d(t), w_avg, w_fast and w_slow over time, one panel per vehicle.
core::Status WriteDivergencePng(const RunRecord& run, const std::string& path);
// True paths (grey) and estimated paths (colour per vehicle) on the final map.
core::Status WritePathsPng(const sim::World& world, const RunRecord& run, const std::string& path);

}  // namespace fleetmap::eval
