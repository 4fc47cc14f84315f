// The evaluation's pictures, as PNG: the current map against the truth (the paper's Fig. 5,
// coloured by correct, missed and false cells), the divergence trace (the paper's Fig. 3) and
// the vehicles' paths.
#pragma once

#include <string>

#include "tools/eval/evaluator.h"

namespace fleetmap::eval {

// Grey map; green: correct added, red: false added, blue: missed added; cyan: correct removed,
// magenta: false removed, orange: missed removed; yellow: static cells erased; purple: actor
// cells mapped.
core::Status WriteOverlayPng(const sim::World& world, const sim::ObservationLog& observations,
                             const RunRecord& run, const std::string& path);
// d(t), w_avg, w_fast and w_slow over time, one panel per vehicle.
core::Status WriteDivergencePng(const RunRecord& run, const std::string& path);
// True paths (grey) and estimated paths (colour per vehicle) on the final map.
core::Status WritePathsPng(const sim::World& world, const RunRecord& run, const std::string& path);

}  // namespace fleetmap::eval
