// A static map modelled on the paper's test hall (Fraunhofer IML LivingLab, Fig. 5a):
// 60 m x 18 m, walls, picking stations seen as ellipses and fixed installations at both
// ends, drawn the way a SLAM map shows them: outlines occupied, insides never observed.
#pragma once

#include "core/map/occupancy_grid.h"

namespace fleetmap::sim {

struct LivingLabOptions {
  double length_m = 60.0;      // hall extent along x
  double width_m = 18.0;       // hall extent along y
  double resolution_m = 0.05;  // cell size
  double wall_thickness_m = 0.2;
  int picking_stations = 4;  // ellipses along the hall's centre line
};

core::OccupancyGrid MakeLivingLabMap(const LivingLabOptions& options = {});

// Marks a pallet (an axis-aligned rectangle centred at (x, y) in world metres) as occupied:
// its outline as a laser sees it, the inside unknown. Returns the number of cells changed.
int AddPalletToMap(core::OccupancyGrid& grid, double x_m, double y_m, double size_x_m = 1.2,
                   double size_y_m = 0.8);

}  // namespace fleetmap::sim
