// `localization_bench --localization_study`: tracking on the paper's five-minute addition
// route, started 0.5 m and 10 deg off, for the localizer's defaults and the alternatives they
// were chosen over (docs/localization.md). One table row per variant on stdout.
#pragma once

namespace fleetmap::bench {

// Prints the table; the program's exit status (0).
int RunLocalizationStudy();

}  // namespace fleetmap::bench
