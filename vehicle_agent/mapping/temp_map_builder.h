// Builds one temporary map at a time, Hector-style, while the divergence detector says the
// map no longer explains the laser: started at the localized pose (the anchor), grown scan by
// scan with odometry as the matching prior, and closed into a core::TempMap cropped to what
// was observed. Bounded: a map that would run out of its area or time is closed, and the
// caller starts the next one.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "core/map/temp_map.h"
#include "vehicle_agent/mapping/local_mapper.h"

namespace fleetmap::vehicle_agent {

struct TempMapBuilderOptions {
  // mapper.map.size_m bounds the map's area (default 20 m). Its matcher leans on odometry
  // more than a log mapper's does (sigma_map 1.0, not 0.25: each end point's map residual
  // counts 16 times less against the odometry prior): people and a forklift walk through a
  // temporary map, and a matcher that follows them slides the map along an aisle. Measured on
  // the fleet scenario, the drift within a map fell from p90 3.7 / max 40 cells to 0.7 / 3.3.
  // Its odometry prior (matcher.prior_sigma_xy_m, _per_m) is the vehicle's to set (agent YAML
  // builder.odometry_sigma_m, _per_m). A tighter one than the default 5 mm + 5 % per scan
  // keeps maps truer (1 mm + 2 %: drift p95 0.066 -> 0.023 m) but costs the office worlds
  // (docs/experiments/2026-12-05-builder-drift.md).
  LocalMapperOptions mapper = [] {
    LocalMapperOptions o;
    o.matcher.sigma_map = 1.0;
    return o;
  }();
  // A map older than this is closed (and another started while the change goes on). 3 s:
  // the aggregator confirms an obstacle by temporary maps of two times, so one pass past a
  // change must give several maps (one map per pass: an object seen once never entered the
  // map); shorter maps also bend less.
  double max_duration_s = 3.0;
  double edge_margin_m = 4.0;  // ... and so is one whose vehicle comes this close to its edge
  double crop_margin_m = 0.2;  // unknown border kept around the observed cells (whole cells)
  core::Status Validate() const;
};

struct BuilderStep {
  core::Pose2 pose_in_temp;  // the vehicle in the temporary map's frame
  bool matched = false;
  bool must_close = false;  // out of area or time: close it (and start another if needed)
};

class TempMapBuilder {
 public:
  explicit TempMapBuilder(const TempMapBuilderOptions& options);

  // Starts a map anchored at the vehicle's localized pose.
  // `anchor_covariance`: how sure localization was of it (travels with the map).
  void Start(const std::string& vehicle_id, int32_t sequence, double stamp_s,
             const core::Pose2& anchor_in_map,
             const std::optional<Eigen::Matrix3d>& anchor_covariance = std::nullopt);
  bool building() const { return mapper_ != nullptr; }

  // `odometry_delta` is the base's motion since the previous scan added, or, for the first
  // scan, since the anchor (none when the anchor is that scan's own pose).
  BuilderStep AddScan(const core::LaserScan& scan, const core::Pose2& odometry_delta,
                      const core::Pose2& scanner_in_base);

  // Closes the map: its grid cropped to the observed cells, its trajectory and times.
  // Nothing (and the builder reset) if no scan was added.
  std::optional<core::TempMap> Close(double stamp_s);

 private:
  TempMapBuilderOptions options_;
  std::unique_ptr<LocalMapper> mapper_;
  core::TempMap pending_;  // everything but the grid, filled while building
};

// The smallest window holding every observed (non-zero) cell, grown by `margin` cells; the
// grid itself when nothing was observed.
core::OccupancyGrid CropToObserved(const core::OccupancyGrid& grid, int margin);

}  // namespace fleetmap::vehicle_agent
