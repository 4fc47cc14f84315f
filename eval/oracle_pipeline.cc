#include <cmath>

#include "eval/pipeline.h"

namespace fleetmap::eval {
namespace {

class OraclePipeline : public Pipeline {
 public:
  std::string name() const override { return "oracle"; }

  void OnEvent(const sim::SimEvent& event) override {
    const auto* scan = std::get_if<sim::ScanEvent>(&event);
    if (!scan) return;
    if (next_pose_s_.size() <= scan->vehicle) next_pose_s_.resize(scan->vehicle + 1, 0.0);
    if (scan->scan.stamp_s < next_pose_s_[scan->vehicle]) return;
    next_pose_s_[scan->vehicle] = scan->scan.stamp_s + 1.0;  // one pose a second per vehicle
    poses_.push_back({"", scan->scan.stamp_s, scan->true_base_pose, scan->true_base_pose});
    vehicles_.push_back(scan->vehicle);
  }

  RunRecord Finish(const sim::Simulator& simulator) override {
    const sim::World& world = simulator.world();
    RunRecord run;
    run.pipeline = name();
    run.RecordVersion(world.static_map());
    core::OccupancyGrid current = world.static_map();
    const core::GridGeometry& g = world.geometry();
    const auto& obs = simulator.observations();
    // First every cell ever seen occupied (an intermediate version), then the last state.
    for (int64_t i = 0; i < g.num_cells(); ++i) {
      const sim::CellObservations* o = obs.Cell(i);
      if (o && o->ever_hit)
        current.SetState({int(i % g.width()), int(i / g.width())}, core::CellState::kOccupied);
    }
    run.RecordVersion(current);
    for (int64_t i = 0; i < g.num_cells(); ++i) {
      const sim::CellObservations* o = obs.Cell(i);
      if (o && o->LastState() == core::CellState::kFree)
        current.SetState({int(i % g.width()), int(i / g.width())}, core::CellState::kFree);
    }
    run.RecordVersion(current);
    AddMerges(world, obs, run);
    for (size_t i = 0; i < poses_.size(); ++i) {
      poses_[i].vehicle_id = world.scenario().vehicles[vehicles_[i]].id;
      run.poses.push_back(poses_[i]);
    }
    return run;
  }

 private:
  // One merge per change a vehicle saw first, placed exactly at the truth.
  static void AddMerges(const sim::World& world, const sim::ObservationLog& obs, RunRecord& run) {
    const auto& objects = world.scenario().objects;
    int seq = 0;
    for (size_t k = 0; k < objects.size(); ++k) {
      for (size_t v = 0; v < world.scenario().vehicles.size(); ++v) {
        for (double seen : {obs.Seen(k, v).appear_seen_s, obs.Seen(k, v).disappear_seen_s}) {
          if (std::isnan(seen)) continue;
          MergeRecord m;
          m.vehicle_id = world.scenario().vehicles[v].id;
          m.tempmap_seq = ++seq;
          m.closed_s = m.merged_s = seen;
          m.accepted = true;
          m.reason = "oracle";
          m.anchor_origin = m.placed_origin = m.true_origin = world.VehicleStateAt(v, seen).pose;
          run.merges.push_back(m);
        }
      }
    }
  }

  std::vector<double> next_pose_s_;
  std::vector<PoseSample> poses_;
  std::vector<size_t> vehicles_;
};

}  // namespace

std::unique_ptr<Pipeline> MakeOraclePipeline() { return std::make_unique<OraclePipeline>(); }

RunRecord RunScenario(const sim::World& world, Pipeline& pipeline, sim::Simulator& simulator,
                      void (*progress)(double t_s)) {
  (void)world;
  double next_report_s = 10.0;
  while (auto event = simulator.Next()) {
    pipeline.OnEvent(*event);
    if (progress && sim::EventTime(*event) >= next_report_s) {
      progress(next_report_s);
      next_report_s += 10.0;
    }
  }
  return pipeline.Finish(simulator);
}

}  // namespace fleetmap::eval
