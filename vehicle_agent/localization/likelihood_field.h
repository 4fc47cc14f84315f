// The likelihood field range-finder model (Probabilistic Robotics, ch. 6.4, table 6.3): a
// beam's end point is scored by its distance d to the nearest occupied cell,
//   p = z_hit N(d; 0, sigma_hit^2) + z_rand / z_max,
// with max-range readings skipped. log p is precomputed per cell from a distance transform
// (OpenCV, kept in the .cc), so scoring a beam is one table lookup: the particle filter's
// measurement update. Unlike the book (and AMCL), d is the distance to the obstacle's
// *surface*, on both sides: an end point inside a thick wall is penalised like one in front
// of it. With d = 0 everywhere inside walls, particles drift into the walls they see (a bias
// of a few cm on 20 cm walls, docs/localization.md). It is blind to removed obstacles (a beam
// through a mapped pallet ends on the wall behind it and scores well); the beam model is not.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <vector>

#include "core/result.h"
#include "vehicle_agent/localization/scan_likelihood.h"

namespace fleetmap::vehicle_agent {

// Defaults are ROS 1 AMCL's (laser_z_hit, laser_z_rand, laser_likelihood_max_dist), except
// sigma_hit_m, beam_stride and max_range_m.
struct LikelihoodFieldOptions {
  double z_hit = 0.95;   // weight of the Gaussian around the nearest surface, >= 0
  double z_rand = 0.05;  // weight of uniform noise over [0, max_range_m), >= 0; z_hit + z_rand > 0
  // Standard deviation of the end-point distance, m, > 0. AMCL: 0.2. 0.1 tracks better
  // (docs/localization.md, "Measured: tracking on the paper's route"): beams on unmapped
  // pallets 0.5 m or more from any wall then pull the pose no more. The S300's own noise is
  // 2 cm.
  double sigma_hit_m = 0.1;
  double max_distance_m = 2.0;  // distances are clamped to this, m, > 0 (off the map: this)
  int beam_stride = 2;          // Score() uses every beam_stride-th beam, >= 1
  double max_range_m = 30.0;    // the model's z_max, m, > 0

  core::Status Validate() const;
};

class LikelihoodField final : public ScanLikelihood {
 public:
  explicit LikelihoodField(const LikelihoodFieldOptions& options);

  void SetMap(const core::OccupancyGrid& map) override;
  // The field of `map` from the cells within the distance cap of `changed` only (SetMap when
  // the geometry differs or there is no map yet): the same values as SetMap, at a cost that
  // grows with the change, not the building.
  void UpdateMap(const core::OccupancyGrid& map, const core::CellWindow& changed) override;
  ScanScore Score(const core::LaserScan& scan, const core::Pose2& scanner_in_map) const override;

  bool has_map() const { return !log_p_.empty(); }
  // Sum of log p over `endpoints_in_base` (beam end points in the vehicle frame, m) with the
  // vehicle at `base_in_map`: the particle filter's inner loop, one lookup per point.
  double LogLikelihood(const std::vector<Eigen::Vector2f>& endpoints_in_base,
                       const core::Pose2& base_in_map) const;
  // log p of one end point in the map frame.
  double LogLikelihoodAt(const Eigen::Vector2d& point_in_map) const;
  // The clamped distance to the nearest occupied cell's surface, m.
  double DistanceAt(const Eigen::Vector2d& point_in_map) const;
  // log p of an end point distance_m from the nearest surface.
  double LogProbabilityOfDistance(double distance_m) const;

 private:
  int ReachCells() const;  // how far a surface's change moves the field, cells
  // Distances and log p of the cells of `out` from the map's surfaces.
  void Recompute(const core::OccupancyGrid& map, const core::CellWindow& out);
  std::optional<size_t> CellOf(const Eigen::Vector2d& point_in_map) const;  // row-major index

  const LikelihoodFieldOptions options_;
  core::GridGeometry geometry_;
  std::vector<float> distance_m_;  // per cell, clamped to max_distance_m
  std::vector<float> log_p_;       // per cell
  double log_p_far_ = 0.0;         // off the map
};

std::unique_ptr<ScanLikelihood> MakeLikelihoodField(const LikelihoodFieldOptions& options);

}  // namespace fleetmap::vehicle_agent
