#include "eval/truth_tempmap_pipeline.h"

#include <algorithm>
#include <cmath>
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
        watches_(world.scenario().vehicles.size(),
                 vehicle_agent::CandidateWatch(world.geometry(), options.candidate_watch)),
        rng_(world.scenario().seed * 7717u + options.seed) {
    run_.pipeline = name();
    run_.RecordVersion(aggregator_.store().current_map());
    run_.RecordSeenFreeDrops({});
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
    finishing_ = true;
    for (size_t v = 0; v < builders_.size(); ++v)
      if (builders_[v].building) Close(v, simulator.now_s());
    return run_;
  }

 private:
  struct Builder {
    bool building = false;
    core::TempMap map;
    core::MovingCells moving;  // of map.grid
    core::Pose2 start_true;    // T in the map frame, the truth
    core::Pose2 last_pose;
    double last_change_s = 0.0;
    double driven_m = 0.0;
    int32_t sequence = 0;
    int extensions = 0;  // times this map was rejected and extended
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
    WatchCandidates(e);
  }

  // The vehicles watch the candidates as the agents do, from where they truly are.
  void WatchCandidates(const sim::ScanEvent& e) {
    vehicle_agent::CandidateWatch& watch = watches_[e.vehicle];
    watch.Observe(e.scan, e.true_scanner_pose);  // with none, it remembers where beams end
    const core::HeldCells held = watch.TakeHeld();
    if (!held.cells.empty()) {
      auto added = aggregator_.ConfirmCandidatesHeld(VehicleId(e.vehicle), held, e.scan.stamp_s);
      if (added.ok() && !added->empty()) {
        run_.RecordVersion(aggregator_.store().current_map());
        ShareCandidates();
      }
    }
    const core::SeenFreeCells seen = watch.TakeSeenFree();
    if (seen.cells.empty()) return;
    auto dropped = aggregator_.DropCandidatesSeenFree(VehicleId(e.vehicle), seen, e.scan.stamp_s);
    if (!dropped.ok() || dropped->empty()) return;
    run_.RecordSeenFreeDrops(*dropped);
    ShareCandidates();
  }

  void ShareCandidates() {
    const std::vector<int64_t> cells = aggregator::CandidateCells(aggregator_.store().candidates());
    for (vehicle_agent::CandidateWatch& watch : watches_) watch.SetCandidates(cells);
  }

  void Start(const sim::ScanEvent& e, const Disagreement& d, Builder& b) {
    const double res = world_.geometry().resolution_m();
    const int cells = static_cast<int>(std::lround(options_.grid_size_m / res));
    const Eigen::Vector2d towards = e.true_base_pose.Inverse().Apply(d.centroid);
    const double distance = towards.norm();
    const Eigen::Vector2d centre =
        distance > 1e-6
            ? Eigen::Vector2d(towards / distance * std::min(distance, options_.grid_lead_m))
            : Eigen::Vector2d::Zero();
    const double half = 0.5 * cells * res;
    b.building = true;
    b.extensions = 0;
    b.start_true = b.last_pose = e.true_base_pose;
    b.last_change_s = e.scan.stamp_s;
    b.driven_m = 0.0;
    b.map = core::TempMap();
    b.map.vehicle_id = VehicleId(e.vehicle);
    b.map.sequence = ++b.sequence;
    b.map.start_s = e.scan.stamp_s;
    b.map.anchor_in_map = Perturb(b.start_true);  // where a localized vehicle thinks T is
    b.map.grid = core::OccupancyGrid(core::GridGeometry(
        res, cells, cells, core::Pose2(centre.x() - half, centre.y() - half, 0)));
    b.moving = core::MovingCells(b.map.grid.geometry(), options_.moving);
  }

  void Insert(const sim::ScanEvent& e, bool changed, Builder& b) {
    const core::Pose2 scanner_in_t = core::Between(b.start_true, e.true_scanner_pose);
    core::InsertScan(e.scan, scanner_in_t, options_.insert,
                     core::BeamDirections(e.scan, scanner_in_t.theta_rad), b.map.grid, &b.moving);
    b.map.trajectory_in_temp.push_back(
        {e.scan.stamp_s, core::Between(b.start_true, e.true_base_pose)});
    b.driven_m += (e.true_base_pose.translation() - b.last_pose.translation()).norm();
    b.last_pose = e.true_base_pose;
    if (changed) b.last_change_s = e.scan.stamp_s;
  }

  bool ShouldClose(const Builder& b, double t) const {
    const double age = t - b.map.start_s, scale = 1.0 + b.extensions;
    return age >= scale * options_.max_duration_s ||
           b.driven_m >= scale * options_.max_distance_m ||
           (age >= scale * options_.min_duration_s &&
            t - b.last_change_s >= options_.quiet_close_s);
  }

  static bool Extendable(aggregator::RejectReason reason) {
    return reason == aggregator::RejectReason::kTooFewStaticLines ||
           reason == aggregator::RejectReason::kAmbiguousShift;
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
    b.moving.Report(b.map.grid);
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
    run_.merges.push_back(m);
    if (m.accepted) {
      ShareCandidates();
      run_.RecordVersion(aggregator_.store().current_map());
      disagreement_.SetMap(aggregator_.store().current_map(), aggregator_.store().semi_static());
    }
    if (report.ok() && !m.accepted && Extendable(report->reason) &&
        b.extensions < options_.max_extensions && !finishing_) {
      ++b.extensions;  // keep building the same map, and send it again later
      b.building = true;
      return;
    }
    b.map = core::TempMap();
  }

  static void Fill(const aggregator::MergeReport& r, const core::Pose2& anchor, MergeRecord& m) {
    m.accepted = r.accepted;
    m.reason = r.accepted
                   ? "accepted"
                   : std::string(aggregator::RejectReasonName(r.reason)) + ": " + r.reason_text;
    m.placed_origin = r.correction * anchor;
    m.anchor_origin = anchor;
    for (const aggregator::LineReportRow& row : r.lines)
      m.lines.push_back(
          {row.temp_line_id, row.static_line_id, row.distance_diff_px, row.angle_diff_deg});
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
  std::vector<vehicle_agent::CandidateWatch> watches_;
  std::mt19937 rng_;
  RunRecord run_;
  bool finishing_ = false;
};

}  // namespace

core::Status TruthTempMapOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(aggregator.Validate());
  FLEETMAP_RETURN_IF_ERROR(insert.Validate());
  if (!(grid_size_m > 0 && grid_size_m <= 100))
    return core::InvalidArgument("grid_size_m must be in (0, 100]");
  if (!(grid_lead_m >= 0)) return core::InvalidArgument("grid_lead_m must be >= 0");
  if (!(max_duration_s > 0 && max_distance_m > 0 && quiet_close_s > 0 && min_duration_s >= 0))
    return core::InvalidArgument("temporary map durations and distances must be positive");
  if (!(anchor_error_max_m >= 0 && anchor_error_max_rad >= 0))
    return core::InvalidArgument("anchor errors must be >= 0");
  if (!(divergence_period_s > 0)) return core::InvalidArgument("divergence_period_s must be > 0");
  FLEETMAP_RETURN_IF_ERROR(candidate_watch.Validate());
  if (max_extensions < 0) return core::InvalidArgument("max_extensions must be >= 0");
  if (trigger.min_run_beams < 1 || trigger.pass_beam_step < 1 || trigger.clearance_cells < 0)
    return core::InvalidArgument("trigger: min_run_beams and pass_beam_step >= 1, clearance >= 0");
  return core::OkStatus();
}

void CoverAnchorErrors(double max_m, double max_rad, aggregator::AggregatorOptions& options) {
  // 2.5 times the error leaves room for a temporary map's own bend; the search reaches 0.2 m
  // past the error (the overlap peak must not lie at the end of its range).
  auto& c = options.confidence;
  c.max_correction_m = std::max(c.max_correction_m, 2.5 * max_m);
  c.max_correction_rad = std::max(c.max_correction_rad, 2.0 * max_rad);
  auto& range = options.alignment.overlap.range_m;
  range = std::max(range, max_m + 0.2);
  // The cell alignment's window too, with a margin (its best pose must not lie at the edge).
  auto& cells = options.cell_alignment;
  cells.range_m = std::max(cells.range_m, max_m + 0.1);
  cells.range_rad = std::max(cells.range_rad, max_rad + 1.0 * M_PI / 180);
}

core::Result<std::unique_ptr<Pipeline>> MakeTruthTempMapPipeline(const sim::World& world,
                                                                 const TruthTempMapOptions& given) {
  FLEETMAP_RETURN_IF_ERROR(given.Validate());
  TruthTempMapOptions options = given;
  CoverAnchorErrors(options.anchor_error_max_m, options.anchor_error_max_rad, options.aggregator);
  auto aggregator = aggregator::Aggregator::Create(world.static_map(), options.aggregator);
  if (!aggregator.ok()) return aggregator.status();
  return std::unique_ptr<Pipeline>(
      std::make_unique<TruthTempMapPipeline>(world, options, std::move(aggregator).value()));
}

}  // namespace fleetmap::eval
