// Whether a beam's end point speaks against a pose on a map that is out of date. A beam that
// ended short of every mapped obstacle, in space the map holds free, met something the map
// lacks (a pallet, a person, a vehicle): the building's change, which the true pose sees as
// often as any other. Only a beam that went through a mapped obstacle, or ended in unknown
// space, says the pose is wrong.
#pragma once

#include <Eigen/Core>

#include "core/map/occupancy_grid.h"
#include "vehicle_agent/localization/likelihood_field.h"

namespace fleetmap::vehicle_agent {

// True when `end` (map frame, m) lies on a free cell of `map` and the beam from `from` to it
// crosses no occupied cell up to margin_m before its end. `field` is the likelihood field of
// the same map: its distances let the walk leap through open space (sphere tracing), a few
// lookups per beam instead of one per cell.
bool EndsShortInFreeSpace(const core::OccupancyGrid& map, const LikelihoodField& field,
                          const Eigen::Vector2d& from, const Eigen::Vector2d& end, double margin_m);

}  // namespace fleetmap::vehicle_agent
