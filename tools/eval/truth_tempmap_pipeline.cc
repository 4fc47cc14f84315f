#include "tools/eval/truth_tempmap_pipeline.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

namespace fleetmap::eval {
namespace {

class TruthTempMapPipeline : public Pipeline {
 public:
  TruthTempMapPipeline(const sim::World& world, const TruthTempMapOptions& options,
                       aggregator::Aggregator aggregator)
      : world_(world),
        options_(options),
        aggregator_(std::move(aggregator)),
        disagreement_(options.trigger),
        builders_(world.scenario().vehicles.size()),
        rng_(world.scenario().seed * 7717u + options.seed) {
    run_.pipeline = name();
    run_.RecordVersion(aggregator_.store().current_map());
    disagreement_.SetMap(aggregator_.store().current_map(), aggregator_.store().semi_static());
  }

  std::string name() const override {
    return std::string("truthmaps-") +
           aggregator::AlignmentModeName(options_.aggregator.alignment.mode);
  }

  void OnEvent(const sim::SimEvent& event) override {
    if (const auto* scan = std::get_if<sim::ScanEvent>(&event)) OnScan(*scan);
  }

  RunRecord Finish(const sim::Simulator& simulator) override {
    for (size_t v = 0; v < builders_.size(); ++v)
      if (builders_[v].building) Close(v, simulator.now_s());
    if (std::getenv("FLEETMAP_DEBUG_BOX")) DebugBox(simulator);  // DEBUG
    return run_;
  }

 private:
  struct Builder {
    bool building = false;
    core::TempMap map;
    core::Pose2 start_true;  // T in the map frame, the truth
    core::Pose2 last_pose;
    double last_change_s = 0.0;
    double driven_m = 0.0;
    int32_t sequence = 0;
    double next_sample_s = 0.0;
    double next_pose_s = 0.0;
  };

  const std::string& VehicleId(size_t v) const { return world_.scenario().vehicles[v].id; }

  void OnScan(const sim::ScanEvent& e) {
    Builder& b = builders_[e.vehicle];
    const double t = e.scan.stamp_s;
    const Disagreement d = disagreement_.Judge(e.scan, e.true_scanner_pose);
    const bool changed = d.changed(options_.trigger);
    if (!b.building && changed) Start(e, d, b);
    if (b.building) Insert(e, changed, b);
    Record(e, d, b);
    if (b.building && ShouldClose(b, t)) Close(e.vehicle, t);
  }

  void Start(const sim::ScanEvent& e, const Disagreement& d, Builder& b) {
    const double res = world_.geometry().resolution_m();
    const int cells = static_cast<int>(std::lround(options_.grid_size_m / res));
    const Eigen::Vector2d towards = e.true_base_pose.Inverse().Apply(d.centroid);
    const double distance = towards.norm();
    const Eigen::Vector2d centre =
        distance > 1e-6 ? Eigen::Vector2d(towards / distance * std::min(distance, options_.grid_lead_m))
                        : Eigen::Vector2d::Zero();
    const double half = 0.5 * cells * res;
    b.building = true;
    b.start_true = b.last_pose = e.true_base_pose;
    b.last_change_s = e.scan.stamp_s;
    b.driven_m = 0.0;
    b.map = core::TempMap();
    b.map.vehicle_id = VehicleId(e.vehicle);
    b.map.sequence = ++b.sequence;
    b.map.start_s = e.scan.stamp_s;
    b.map.grid = core::OccupancyGrid(
        core::GridGeometry(res, cells, cells, core::Pose2(centre.x() - half, centre.y() - half, 0)));
  }

  void Insert(const sim::ScanEvent& e, bool changed, Builder& b) {
    const core::Pose2 scanner_in_t = core::Between(b.start_true, e.true_scanner_pose);
    core::InsertScan(e.scan, scanner_in_t, options_.insert, b.map.grid);
    b.map.trajectory_in_temp.push_back(
        {e.scan.stamp_s, core::Between(b.start_true, e.true_base_pose)});
    b.driven_m += (e.true_base_pose.translation() - b.last_pose.translation()).norm();
    b.last_pose = e.true_base_pose;
    if (changed) b.last_change_s = e.scan.stamp_s;
  }

  bool ShouldClose(const Builder& b, double t) const {
    const double age = t - b.map.start_s;
    return age >= options_.max_duration_s || b.driven_m >= options_.max_distance_m ||
           (age >= options_.min_duration_s && t - b.last_change_s >= options_.quiet_close_s);
  }

  core::Pose2 Perturb(const core::Pose2& truth) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double r = options_.anchor_error_max_m * unit(rng_);
    const double direction = 2 * M_PI * unit(rng_);
    const double turn = options_.anchor_error_max_rad * (2 * unit(rng_) - 1);
    return {truth.x_m + r * std::cos(direction), truth.y_m + r * std::sin(direction),
            core::NormalizeAngle(truth.theta_rad + turn)};
  }

  void Close(size_t v, double t) {
    Builder& b = builders_[v];
    b.building = false;
    b.map.end_s = t;
    b.map.anchor_in_map = Perturb(b.start_true);
    MergeRecord m;
    m.vehicle_id = b.map.vehicle_id;
    m.tempmap_seq = b.map.sequence;
    m.closed_s = m.merged_s = t;
    m.true_origin = b.start_true;
    auto report = aggregator_.Submit(b.map, t);
    if (!report.ok()) {
      m.reason = report.status().ToString();
    } else {
      Fill(*report, b.map.anchor_in_map, m);
    }
    if (std::getenv("FLEETMAP_DEBUG_MERGES") && report.ok()) DebugPrint(*report, m);  // DEBUG
    run_.merges.push_back(m);
    if (m.accepted) {
      run_.RecordVersion(aggregator_.store().current_map());
      disagreement_.SetMap(aggregator_.store().current_map(), aggregator_.store().semi_static());
    }
    b.map = core::TempMap();
  }

  static void DebugPrint(const aggregator::MergeReport& r, const MergeRecord& m) {  // DEBUG
    const core::Pose2 e = core::Between(m.true_origin, m.placed_origin);
    const auto& a = r.alignment;
    std::fprintf(stderr,
                 "merge %d: res (%.2f %.2f %.3f) dtheta %.3f dx %.3f dy %.3f rounds %d overlap %d "
                 "shift %.3f score %.3f runner %.3f zero %.3f dist %.3f lines %zu expl %.2f->%.2f %s\n",
                 m.tempmap_seq, e.x_m / 0.05, e.y_m / 0.05, e.theta_rad * 180 / M_PI,
                 a.dtheta_rad * 180 / M_PI, a.dx_m, a.dy_m, a.rounds, a.shift_by_overlap,
                 a.overlap.shift_m, a.overlap.score, a.overlap.lowest, a.overlap.at_zero, a.overlap.Prominence(), a.matches.size(),
                 r.confidence.explained_before, r.confidence.explained_after, m.reason.c_str());
    for (const auto& mt : a.matches)
      std::fprintf(stderr, "   t%d s%d len %.2f off %.3f ang %.3f n (%.2f %.2f)\n", mt.temp_index,
                   mt.static_index, mt.weight_m, mt.offset_m / 0.05, mt.angle_diff_rad * 180 / M_PI,
                   mt.normal.x(), mt.normal.y());
  }

  void DebugBox(const sim::Simulator& simulator) const {  // DEBUG
    double x0, y0, x1, y1;
    std::sscanf(std::getenv("FLEETMAP_DEBUG_BOX"), "%lf,%lf,%lf,%lf", &x0, &y0, &x1, &y1);
    const auto& g = world_.geometry();
    const auto& st = aggregator_.store();
    for (double y = y1; y >= y0; y -= 0.05) {
      for (double x = x0; x <= x1; x += 0.05) {
        const auto c = g.WorldToCell({x + 0.001, y + 0.001});
        const int64_t i = g.Index(c);
        const auto* o = simulator.observations().Cell(i);
        const bool truth = o && o->LastState() == core::CellState::kOccupied;
        bool was = false;
        for (const auto& ev : st.provenance().HistoryOf(i)) was |= ev.kind == aggregator::CellChangeKind::kAdded;
        const bool truth_removed = o && o->ever_hit && o->LastState() == core::CellState::kFree;
        char ch = st.semi_static()[i] ? (truth ? '#' : 'X') : was ? (truth_removed ? 'R' : 'r') : st.candidate_mask()[i] ? (truth ? 'c' : 'k') : (truth ? 'o' : truth_removed ? 'm' : '.');
        std::fputc(ch, stderr);
      }
      std::fputc('\n', stderr);
    }
  }

  static void Fill(const aggregator::MergeReport& r, const core::Pose2& anchor, MergeRecord& m) {
    m.accepted = r.accepted;
    m.reason = r.accepted ? "accepted" : std::string(aggregator::RejectReasonName(r.reason)) + ": " +
                                             r.reason_text;
    m.placed_origin = r.correction * anchor;
    for (const aggregator::LineReportRow& row : r.lines)
      m.lines.push_back({row.temp_line_id, row.static_line_id, row.distance_diff_px,
                         row.angle_diff_deg});
    m.cells_added = r.cells_added;
    m.cells_removed = r.cells_removed;
  }

  // A divergence-like trace (the disagreeing fraction of the beams) and the poses.
  void Record(const sim::ScanEvent& e, const Disagreement& d, Builder& b) {
    const double t = e.scan.stamp_s;
    if (t >= b.next_sample_s) {
      b.next_sample_s = t + options_.divergence_period_s;
      const double fraction = e.scan.size() ? double(d.disagreeing_beams) / e.scan.size() : 0.0;
      run_.divergence.push_back(
          {VehicleId(e.vehicle), t, 1.0 - fraction, 1.0, 1.0 - fraction, fraction, b.building});
    }
    if (t >= b.next_pose_s) {
      b.next_pose_s = t + 1.0;
      run_.poses.push_back({VehicleId(e.vehicle), t, e.true_base_pose, e.true_base_pose});
    }
  }

  const sim::World& world_;
  TruthTempMapOptions options_;
  aggregator::Aggregator aggregator_;
  ScanDisagreement disagreement_;
  std::vector<Builder> builders_;
  std::mt19937 rng_;
  RunRecord run_;
};

}  // namespace

core::Status TruthTempMapOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(aggregator.Validate());
  FLEETMAP_RETURN_IF_ERROR(insert.Validate());
  if (!(grid_size_m > 0 && grid_size_m <= 100)) return core::InvalidArgument("grid_size_m must be in (0, 100]");
  if (!(grid_lead_m >= 0)) return core::InvalidArgument("grid_lead_m must be >= 0");
  if (!(max_duration_s > 0 && max_distance_m > 0 && quiet_close_s > 0 && min_duration_s >= 0))
    return core::InvalidArgument("temporary map durations and distances must be positive");
  if (!(anchor_error_max_m >= 0 && anchor_error_max_rad >= 0))
    return core::InvalidArgument("anchor errors must be >= 0");
  if (!(divergence_period_s > 0)) return core::InvalidArgument("divergence_period_s must be > 0");
  if (trigger.min_run_beams < 1 || trigger.pass_beam_step < 1 || trigger.clearance_cells < 0)
    return core::InvalidArgument("trigger: min_run_beams and pass_beam_step >= 1, clearance >= 0");
  return core::OkStatus();
}

core::Result<std::unique_ptr<Pipeline>> MakeTruthTempMapPipeline(const sim::World& world,
                                                                 const TruthTempMapOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  auto aggregator = aggregator::Aggregator::Create(world.static_map(), options.aggregator);
  if (!aggregator.ok()) return aggregator.status();
  return std::unique_ptr<Pipeline>(
      std::make_unique<TruthTempMapPipeline>(world, options, std::move(aggregator).value()));
}

}  // namespace fleetmap::eval
