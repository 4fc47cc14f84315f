#include "eval/agents_pipeline.h"

#include <cmath>

#include "eval/anchor_consistency.h"
#include "eval/tempmap_drift.h"
#include "eval/tile_transport.h"

namespace fleetmap::eval {
namespace {

class AgentsPipeline : public Pipeline {
 public:
  AgentsPipeline(const sim::World& world, const AgentsPipelineOptions& options,
                 aggregator::Aggregator aggregator)
      : world_(world), options_(options), aggregator_(std::move(aggregator)) {
    run_.pipeline = name();
    run_.RecordVersion(aggregator_.store().current_map());
    run_.RecordSeenFreeDrops({});
    for (const sim::VehicleSpec& v : world.scenario().vehicles) {
      vehicle_agent::AgentPipelineOptions o = options.agent;
      o.vehicle_id = v.id;
      o.scanner_in_base = v.scanner_mount;
      agents_.push_back(std::make_unique<vehicle_agent::AgentPipeline>(o));
      const core::Pose2 start = world.VehicleStateAt(agents_.size() - 1, 0.0).pose;
      const Eigen::Matrix3d cov = Eigen::Vector3d(std::pow(options.initial_sigma_xy_m, 2),
                                                  std::pow(options.initial_sigma_xy_m, 2),
                                                  std::pow(options.initial_sigma_theta_rad, 2))
                                      .asDiagonal();
      (void)agents_.back()->InitializeAt(start, cov);
      (void)agents_.back()->SetMap(aggregator_.store().current_map(), Version());
    }
    next_divergence_s_.assign(agents_.size(), 0.0);
    next_pose_s_.assign(agents_.size(), 0.0);
  }

  std::string name() const override { return "agents"; }

  void OnEvent(const sim::SimEvent& event) override {
    if (const auto* o = std::get_if<sim::OdometryEvent>(&event)) {
      agents_[o->vehicle]->AddOdometry({o->stamp_s, o->odom_pose, o->v_mps, o->omega_radps});
    } else if (const auto* e = std::get_if<sim::ExternalPoseEvent>(&event)) {
      (void)agents_[e->vehicle]->AddExternalPose(
          {e->stamp_s, e->pose, Eigen::Matrix3d::Identity() * 1e-3, Version()});
    } else if (const auto* s = std::get_if<sim::ScanEvent>(&event)) {
      OnScan(*s);
    }
  }

  RunRecord Finish(const sim::Simulator& simulator) override {
    for (size_t v = 0; v < agents_.size(); ++v) {
      if (auto map = agents_[v]->Flush(simulator.now_s())) Merge(v, *map, simulator.now_s());
    }
    return std::move(run_);
  }

 private:
  int32_t Version() const { return static_cast<int32_t>(aggregator_.store().version()); }

  void OnScan(const sim::ScanEvent& s) {
    const size_t v = s.vehicle;
    const double t = s.scan.stamp_s;
    vehicle_agent::AgentStep step = agents_[v]->AddScan(s.scan);
    const std::string& id = world_.scenario().vehicles[v].id;
    if (t >= next_divergence_s_[v]) {
      const auto& d = step.divergence;
      run_.divergence.push_back({id, t, d.w_avg, d.w_slow, d.w_fast, d.d, step.building});
      next_divergence_s_[v] = t + options_.divergence_period_s;
    }
    if (t >= next_pose_s_[v]) {
      run_.poses.push_back({id, t, step.pose.pose_in_map, s.true_base_pose});
      next_pose_s_[v] = t + options_.pose_period_s;
    }
    if (step.closed_map) Merge(v, *step.closed_map, t);
    ReportSeenFree(v, t);
    ReportHeld(v, t);
  }

  // What a vehicle's beams saw free goes to the aggregator at once (in-process, no link).
  void ReportSeenFree(size_t v, double now_s) {
    const core::SeenFreeCells seen = agents_[v]->TakeSeenFree();
    if (seen.cells.empty()) return;
    auto dropped =
        aggregator_.DropCandidatesSeenFree(world_.scenario().vehicles[v].id, seen, now_s);
    if (!dropped.ok() || dropped->empty()) return;
    run_.RecordSeenFreeDrops(*dropped);
    ShareCandidates();
  }

  // ... and so does what they saw held.
  void ReportHeld(size_t v, double now_s) {
    const core::HeldCells held = agents_[v]->TakeHeld();
    if (held.cells.empty()) return;
    auto added = aggregator_.ConfirmCandidatesHeld(world_.scenario().vehicles[v].id, held, now_s);
    if (!added.ok() || added->empty()) return;
    run_.RecordVersion(aggregator_.store().current_map());
    ShareCandidates();
  }

  void ShareCandidates() {
    const std::vector<int64_t> cells = aggregator::CandidateCells(aggregator_.store().candidates());
    for (auto& agent : agents_) agent->SetCandidates(cells);
  }

  void Merge(size_t v, const core::TempMap& map, double now_s) {
    MergeRecord record;
    record.vehicle_id = map.vehicle_id;
    record.tempmap_seq = map.sequence;
    record.closed_s = map.end_s;
    record.merged_s = now_s;  // in-process: merged as soon as closed
    // Where the map truly lies: the grid's corner placed by the vehicle's true pose at the
    // map's start, which defines its frame T (as the recorded run's evaluation reads it).
    record.true_origin = world_.VehicleStateAt(v, map.start_s).pose * map.grid.geometry().origin();
    record.anchor_origin = map.PlacedGeometry().origin();
    if (map.anchor_covariance)
      record.anchor_nees = AnchorNees(map.anchor_in_map, *map.anchor_covariance,
                                      world_.VehicleStateAt(v, map.start_s).pose);
    const TempMapDrift drift = BuilderDrift(
        map.trajectory_in_temp, [&](double t) { return world_.VehicleStateAt(v, t).pose; });
    record.drift_m = drift.translation_m;
    record.drift_deg = drift.rotation_deg;
    // The aggregator gets what travels: the map cut into tiles and put together again.
    auto received = AsReceived(map);
    if (!received.ok()) {
      record.reason = received.status().ToString();
      run_.merges.push_back(record);
      return;
    }
    auto report = aggregator_.Submit(*received, now_s);
    if (!report.ok()) {
      record.reason = report.status().ToString();
      run_.merges.push_back(record);
      return;
    }
    record.accepted = report->accepted;
    record.reason = report->reason_text;
    record.placed_origin = report->correction * map.PlacedGeometry().origin();
    record.correction_mahalanobis_sq = report->confidence.anchor_mahalanobis_sq;
    record.fit_gain = report->confidence.overlap_gain;
    for (const auto& l : report->lines)
      record.lines.push_back(
          {l.temp_line_id, l.static_line_id, l.distance_diff_px, l.angle_diff_deg});
    record.cells_added = report->cells_added;
    record.cells_removed = report->cells_removed;
    run_.merges.push_back(record);
    if (!report->accepted) return;
    ShareCandidates();
    run_.RecordVersion(aggregator_.store().current_map());
    // The agents' map follows the merge's tiles, as a vehicle's replica does.
    core::CellWindow changed;
    for (const core::EncodedTile& tile : report->delta.tiles)
      changed = core::Union(changed, aggregator_.store().layout().Window(tile.index));
    for (auto& agent : agents_)
      (void)agent->UpdateMap(aggregator_.store().current_map(), Version(), changed);
  }

  const sim::World& world_;
  AgentsPipelineOptions options_;
  aggregator::Aggregator aggregator_;
  std::vector<std::unique_ptr<vehicle_agent::AgentPipeline>> agents_;
  std::vector<double> next_divergence_s_, next_pose_s_;
  RunRecord run_;
};

}  // namespace

core::Result<std::unique_ptr<Pipeline>> MakeAgentsPipeline(const sim::World& world,
                                                           const AgentsPipelineOptions& options) {
  auto aggregator = aggregator::Aggregator::Create(world.static_map(), options.aggregator);
  if (!aggregator.ok()) return aggregator.status();
  return std::unique_ptr<Pipeline>(
      std::make_unique<AgentsPipeline>(world, options, std::move(aggregator).value()));
}

}  // namespace fleetmap::eval
