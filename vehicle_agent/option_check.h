// One line per option check, so that every Validate() names the bad field and its value:
// "BeamModelOptions.sigma_hit_m = -1: must be > 0".
#pragma once

#include <string>

#include "core/result.h"

namespace fleetmap::vehicle_agent {

// Ok when `ok`; otherwise InvalidArgument naming `field`, its `value` and the `requirement`.
core::Status CheckOption(bool ok, const std::string& field, double value,
                         const std::string& requirement);

}  // namespace fleetmap::vehicle_agent
