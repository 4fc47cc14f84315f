#include "core/map/log_odds.h"

#include <string>

namespace fleetmap::core {

Status OccupancyThresholds::Validate() const {
  if (!(free_probability > 0.0 && free_probability < occupied_probability &&
        occupied_probability < 1.0)) {
    return InvalidArgument("thresholds need 0 < free_probability (" +
                           std::to_string(free_probability) + ") < occupied_probability (" +
                           std::to_string(occupied_probability) + ") < 1");
  }
  return OkStatus();
}

Status LogOddsLimits::Validate() const {
  if (!(std::isfinite(min_log_odds) && std::isfinite(max_log_odds) && min_log_odds < 0.0f &&
        max_log_odds > 0.0f)) {
    return InvalidArgument("log-odds limits need min_log_odds < 0 < max_log_odds");
  }
  return OkStatus();
}

}  // namespace fleetmap::core
