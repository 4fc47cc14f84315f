// `localization_bench --divergence_study`: simulated runs (an empty hall, pallets appearing,
// the LivingLab addition, removal and fleet scenarios) recorded once as W_avg traces, then
// replayed through every divergence detector variant; per variant and trace, the starts, the
// false starts, the changes detected and how late, and the share of time spent building. The
// table behind the detector's defaults (vehicle_agent/divergence.h), on stdout.
#pragma once

namespace fleetmap::bench {

// Prints the table; the program's exit status (0).
int RunDivergenceStudy();

}  // namespace fleetmap::bench
