// A map at a coarser resolution, for the resolution sweep (a 10 cm map from a 5 cm one).
#pragma once

#include "core/map/occupancy_grid.h"

namespace fleetmap::ops::lan {

// Each cell of the result covers factor x factor cells of `fine` (fewer at the far edges);
// same origin. It is occupied when any of them is occupied (walls stay closed), else free
// when at least half of them are free, else unknown. factor >= 1.
core::OccupancyGrid ResampleMap(const core::OccupancyGrid& fine, int factor);

}  // namespace fleetmap::ops::lan
