// Placement (the paper, Sec. 3.4: "the temporary map is transformed into the static map
// coordinate system, utilizing the first robot location"): checks a temporary map from
// outside before anything else reads it, and resamples its evidence into the static map's
// cells once it is placed by correction * anchor.
#pragma once

#include <vector>

#include "core/map/temp_map.h"

namespace fleetmap::aggregator {

struct PlacementOptions {
  double resolution_tolerance = 1e-6;  // relative difference allowed from the static map's
  int64_t max_cells = 4'000'000;       // more cells is absurd (100 m x 100 m at 5 cm)
  double max_extent_m = 100.0;         // longest side of a temporary map, metres
  // Of the cells the temporary map observed (log-odds != 0), at least this fraction must
  // lie inside the static map when placed by the anchor.
  double min_inside_fraction = 0.8;
  core::Status Validate() const;
};

// InvalidArgument / OutOfRange naming what is wrong: missing vehicle id, invalid or absurd
// geometry, another resolution, a non-finite anchor, cell or trajectory pose, times out of
// order, nothing observed, or lying (mostly) outside the static map.
core::Status CheckTempMap(const core::TempMap& map, const core::GridGeometry& static_geometry,
                          const PlacementOptions& options);

// The temporary map's evidence on the static map's cells.
struct PlacedEvidence {
  int map_width = 0;            // the static map's width, for its row-major cell indices
  double resolution_m = 0.05;   // the static map's cell size
  core::CellWindow window;      // static cells the placed temporary grid covers (clipped)
  std::vector<float> log_odds;  // per window cell, row-major: the temporary cell containing
                                // the static cell's centre, 0 where there is none
  float at(const core::CellIndex& static_cell) const {
    return log_odds[static_cast<size_t>(static_cell.y - window.y0) * window.width +
                    (static_cell.x - window.x0)];
  }
};

// Nearest-neighbour resampling (each static cell takes the temporary cell under its centre).
// The map must have passed CheckTempMap against the same geometry.
PlacedEvidence PlaceEvidence(const core::TempMap& map, const core::Pose2& correction,
                             const core::GridGeometry& static_geometry);

}  // namespace fleetmap::aggregator
