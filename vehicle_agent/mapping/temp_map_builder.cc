#include "vehicle_agent/mapping/temp_map_builder.h"

#include <algorithm>
#include <cmath>

namespace fleetmap::vehicle_agent {

core::Status TempMapBuilderOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(mapper.Validate());
  if (!(max_duration_s > 0 && edge_margin_m >= 0 && edge_margin_m < mapper.map.size_m / 2 &&
        crop_margin_m >= 0)) {
    return core::InvalidArgument(
        "temp map builder: max_duration_s > 0, 0 <= edge_margin_m < "
        "half the map size, crop_margin_m >= 0");
  }
  return core::OkStatus();
}

TempMapBuilder::TempMapBuilder(const TempMapBuilderOptions& options) : options_(options) {}

void TempMapBuilder::Start(const std::string& vehicle_id, int32_t sequence, double stamp_s,
                           const core::Pose2& anchor_in_map,
                           const std::optional<Eigen::Matrix3d>& anchor_covariance) {
  mapper_ = std::make_unique<LocalMapper>(options_.mapper);  // frame T: the vehicle at start
  pending_ = core::TempMap();
  pending_.vehicle_id = vehicle_id;
  pending_.sequence = sequence;
  pending_.anchor_in_map = anchor_in_map;
  pending_.anchor_covariance = anchor_covariance;
  pending_.start_s = pending_.end_s = stamp_s;
}

BuilderStep TempMapBuilder::AddScan(const core::LaserScan& scan, const core::Pose2& odometry_delta,
                                    const core::Pose2& scanner_in_base) {
  assert(building());
  // Frame T is the vehicle where the anchor was taken: the first scan's odometry_delta places
  // it there (none when the anchor is that scan's own pose).
  const ScanUpdate update = mapper_->AddScan(scan, odometry_delta, scanner_in_base);
  pending_.trajectory_in_temp.push_back({scan.stamp_s, update.pose});
  pending_.end_s = std::max(pending_.end_s, scan.stamp_s);
  BuilderStep step{update.pose, update.matched, false};
  step.must_close = scan.stamp_s - pending_.start_s >= options_.max_duration_s ||
                    !mapper_->map().Inside(update.pose.translation(), options_.edge_margin_m);
  return step;
}

std::optional<core::TempMap> TempMapBuilder::Close(double stamp_s) {
  if (!building()) return std::nullopt;
  std::optional<core::TempMap> out;
  if (!pending_.trajectory_in_temp.empty()) {
    pending_.end_s = std::max(pending_.end_s, stamp_s);
    core::OccupancyGrid evidence = mapper_->map().finest();
    mapper_->map().moving().Report(evidence);  // what moved is no obstacle (moving_cells.h)
    const int margin_cells = static_cast<int>(
        std::ceil(core::MetresInCells(options_.crop_margin_m, evidence.geometry().resolution_m())));
    pending_.grid = CropToObserved(evidence, margin_cells);
    out = std::move(pending_);
  }
  mapper_.reset();
  pending_ = core::TempMap();
  return out;
}

core::OccupancyGrid CropToObserved(const core::OccupancyGrid& grid, int margin) {
  const core::GridGeometry& g = grid.geometry();
  int x0 = g.width(), y0 = g.height(), x1 = -1, y1 = -1;
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      if (grid.log_odds({x, y}) == 0.0f) continue;
      x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
    }
  }
  if (x1 < 0) return grid;
  x0 = std::max(0, x0 - margin), y0 = std::max(0, y0 - margin);
  x1 = std::min(g.width() - 1, x1 + margin), y1 = std::min(g.height() - 1, y1 + margin);
  const double res = g.resolution_m();
  const core::Pose2 origin = g.origin() * core::Pose2(x0 * res, y0 * res, 0);
  core::OccupancyGrid out(core::GridGeometry(res, x1 - x0 + 1, y1 - y0 + 1, origin), grid.limits());
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) out.SetLogOdds({x - x0, y - y0}, grid.log_odds({x, y}));
  return out;
}

}  // namespace fleetmap::vehicle_agent
