#include "vehicle_agent/agent_pipeline.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "vehicle_agent/localization/input_guard.h"

namespace fleetmap::vehicle_agent {

core::Status AgentPipelineOptions::Validate() const {
  if (vehicle_id.empty()) return core::InvalidArgument("agent: vehicle_id is empty");
  if (!scanner_in_base.IsFinite())
    return core::InvalidArgument("agent: scanner_in_base is not finite");
  if (first_sequence < 1) return core::InvalidArgument("agent: first_sequence must be >= 1");
  if (!(max_scan_gap_s > 0)) return core::InvalidArgument("agent: max_scan_gap_s must be > 0");
  FLEETMAP_RETURN_IF_ERROR(localizer.Validate().WithContext("agent.localizer"));
  FLEETMAP_RETURN_IF_ERROR(divergence.Validate().WithContext("agent.divergence"));
  FLEETMAP_RETURN_IF_ERROR(builder.Validate().WithContext("agent.builder"));
  if (!(candidate_watch_max_sigma_m > 0))
    return core::InvalidArgument("agent: candidate_watch_max_sigma_m must be > 0");
  return candidate_watch.Validate().WithContext("agent.candidate_watch");
}

AgentPipeline::AgentPipeline(const AgentPipelineOptions& options)
    : options_(options),
      localizer_(options.localizer),
      divergence_(options.divergence),
      builder_(options.builder),
      next_sequence_(options.first_sequence) {}

core::Status AgentPipeline::SetMap(const core::OccupancyGrid& map, int32_t version) {
  // Temporary maps are built at the current map's resolution, so that they merge cell for cell.
  options_.builder.mapper.map.resolution_m = map.geometry().resolution_m();
  if (!watch_ || !(watch_->geometry() == map.geometry())) {
    watch_.emplace(map.geometry(), options_.candidate_watch);
    watch_->SetCandidates(candidates_);
  }
  return localizer_.SetMap(map, version);
}

core::Status AgentPipeline::UpdateMap(const core::OccupancyGrid& map, int32_t version,
                                      const core::CellWindow& changed) {
  if (!watch_ || !(watch_->geometry() == map.geometry())) return SetMap(map, version);
  return localizer_.UpdateMap(map, version, changed);
}

core::Status AgentPipeline::InitializeAt(const core::Pose2& pose, const Eigen::Matrix3d& cov) {
  return localizer_.InitializeAt(pose, cov);
}

core::Status AgentPipeline::AddExternalPose(const core::PoseEstimate& pose) {
  return localizer_.AddExternalPose(pose);
}

void AgentPipeline::AddOdometry(const core::OdometrySample& odom) {
  localizer_.AddOdometry(odom);  // every increment, and bad samples counted there
  if (!odom.Validate().ok()) return;
  odom_ = odom;
}

void AgentPipeline::SetCandidates(const std::vector<int64_t>& cells) {
  candidates_ = cells;  // for a watch made later (the first map may come after them)
  if (watch_) watch_->SetCandidates(cells);
}

CandidatesSeenFree AgentPipeline::TakeSeenFree() {
  return watch_ ? watch_->TakeSeenFree() : CandidatesSeenFree{};
}

CandidatesHeld AgentPipeline::TakeHeld() { return watch_ ? watch_->TakeHeld() : CandidatesHeld{}; }

bool AgentPipeline::WellLocalized(const core::PoseEstimate& pose) const {
  const double sigma_m = std::sqrt(std::max(pose.covariance(0, 0), pose.covariance(1, 1)));
  return sigma_m <= options_.candidate_watch_max_sigma_m;
}

void AgentPipeline::WatchCandidates(const core::LaserScan& scan, const core::PoseEstimate& pose) {
  if (!watch_) return;  // with no candidates yet it remembers where beams end
  watch_->Observe(scan, pose.pose_in_map * options_.scanner_in_base);
}

void AgentPipeline::StartMap(double stamp_s, const core::PoseEstimate& anchor) {
  builder_ = TempMapBuilder(options_.builder);
  builder_.Start(options_.vehicle_id, next_sequence_++, stamp_s, anchor.pose_in_map,
                 anchor.covariance);
  clean_odom_at_builder_ = localizer_.clean_odometry();  // the anchor is the pose at this scan
  ++counters_.temp_maps_started;
}

AgentStep AgentPipeline::AddScan(const core::LaserScan& scan) {
  ++counters_.scans;
  AgentStep step;
  const LocalizerResult located = localizer_.Update(odom_, scan, options_.scanner_in_base);
  step.pose = located.estimate;
  step.localization = located.stats;
  if (located.stats.relocalized) {
    // Everything since the vehicle got lost was seen from a wrong pose.
    divergence_.Reset();
    if (builder_.building()) {
      builder_ = TempMapBuilder(options_.builder);
      ++counters_.temp_maps_dropped;
    }
  }
  const bool well_localized = WellLocalized(step.pose) && !located.stats.lost;
  step.well_localized = well_localized;
  step.divergence =
      divergence_.Update(scan.stamp_s, located.stats.w_avg, odom_.omega_radps, well_localized);
  const bool valid = scan.Validate().ok();
  const std::optional<double> previous_s = last_scan_stamp_s_;
  if (valid) last_scan_stamp_s_ = scan.stamp_s;
  if (valid && previous_s && builder_.building() &&
      (IsClockStepBack(scan.stamp_s, *previous_s) ||
       scan.stamp_s - *previous_s > options_.max_scan_gap_s)) {
    // The clock was set back (a map's times must run forward) or no scan came for a while
    // (the map would be bridged blind): this map closes at its last scan, and the change goes
    // on in a new one from this scan.
    step.closed_map = builder_.Close(*previous_s);
    ++counters_.temp_maps_split;
    continue_change_ = true;
  }
  const bool continues = std::exchange(continue_change_, false) && step.divergence.building &&
                         !step.divergence.stopped;
  if ((step.divergence.started || continues) && !builder_.building())
    StartMap(scan.stamp_s, step.pose);
  if (builder_.building() && step.divergence.accepted && valid) {
    // From the localizer's clean odometry (a jump the tracker refused must not tear the
    // temporary map either), since the anchor or the map's last scan: a scan left out still
    // moved the vehicle.
    const core::Pose2 odometry_delta =
        core::Between(clean_odom_at_builder_, localizer_.clean_odometry());
    clean_odom_at_builder_ = localizer_.clean_odometry();
    const BuilderStep built = builder_.AddScan(scan, odometry_delta, options_.scanner_in_base);
    if (built.must_close && !step.divergence.stopped) {
      // Out of area or time while the change goes on: close this map and go on in a new one
      // from the next scan. Anchored here instead, it would hold the next scan's view in a
      // frame a scan's motion behind its anchor (up to 2 degrees in a turn), or that motion
      // from the odometry, whose heading errs by degrees per metre.
      step.closed_map = builder_.Close(scan.stamp_s);
      ++counters_.temp_maps_split;
      continue_change_ = true;
    }
  }
  if (step.divergence.stopped && builder_.building())
    step.closed_map = builder_.Close(scan.stamp_s);
  if (step.closed_map) ++counters_.temp_maps_closed;
  step.building = builder_.building();
  if (valid && well_localized) WatchCandidates(scan, step.pose);
  return step;
}

std::optional<core::TempMap> AgentPipeline::Flush(double stamp_s) {
  auto closed = builder_.Close(stamp_s);
  if (closed) ++counters_.temp_maps_closed;
  return closed;
}

}  // namespace fleetmap::vehicle_agent
