#include "eval/evaluator.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

namespace fleetmap::eval {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

void ScoreAlignment(const std::vector<MergeRecord>& merges, double resolution_m, EvalReport& r) {
  std::vector<double> trans, cells, rot, anchor_cells;
  std::vector<double> drift_m, drift_deg, nees;
  for (const MergeRecord& m : merges) {
    if (std::isfinite(m.anchor_nees)) nees.push_back(m.anchor_nees);
    if (std::isfinite(m.drift_m)) drift_m.push_back(m.drift_m);
    if (std::isfinite(m.drift_deg)) drift_deg.push_back(m.drift_deg);
    if (!m.accepted) {
      ++r.merges_rejected;
      continue;
    }
    ++r.merges_accepted;
    const core::Pose2 residual = core::Between(m.placed_origin, m.true_origin);
    // Below a nanometre is rounding in the pose algebra, not an alignment error.
    const double t = std::hypot(residual.x_m, residual.y_m) < 1e-9
                         ? 0.0
                         : std::hypot(residual.x_m, residual.y_m);
    trans.push_back(t);
    cells.push_back(t / resolution_m);
    rot.push_back(std::abs(residual.theta_rad) * kRadToDeg);
    const core::Pose2 anchor = core::Between(m.anchor_origin, m.true_origin);
    anchor_cells.push_back(std::hypot(anchor.x_m, anchor.y_m) / resolution_m);
  }
  r.align_translation_m = Summarize(trans);
  r.align_translation_cells = Summarize(cells);
  r.align_rotation_deg = Summarize(rot);
  r.anchor_translation_cells = Summarize(anchor_cells);
  r.anchor_nees = Summarize(nees);
  r.tempmap_drift_m = Summarize(drift_m);
  r.tempmap_drift_deg = Summarize(drift_deg);
}

// Per vehicle: the times at which it started a temporary map (d rose above 0), and whether
// it was building at a given time. The map open from a vehicle's first sample on is the one
// every vehicle builds at start-up (DivergenceOptions::map_at_start), not a trigger.
struct Triggers {
  std::vector<double> starts;
  std::vector<std::pair<double, bool>> samples;  // (t, building)
};

std::map<std::string, Triggers> CollectTriggers(const std::vector<DivergenceSample>& samples) {
  std::map<std::string, Triggers> by_vehicle;
  for (const DivergenceSample& s : samples) {
    Triggers& t = by_vehicle[s.vehicle_id];
    if (s.building && !t.samples.empty() && !t.samples.back().second) t.starts.push_back(s.t_s);
    t.samples.emplace_back(s.t_s, s.building);
  }
  return by_vehicle;
}

void ScoreDetection(const sim::World& world, const sim::ObservationLog& obs, const RunRecord& run,
                    const EvalOptions& options, EvalReport& r) {
  const auto triggers = CollectTriggers(run.divergence);
  const auto& vehicles = world.scenario().vehicles;
  std::vector<double> latencies;
  std::map<std::string, std::vector<double>> seen_times;
  for (size_t k = 0; k < world.scenario().objects.size(); ++k) {
    for (size_t v = 0; v < vehicles.size(); ++v) {
      const sim::ObjectChangeSeen& seen = obs.Seen(k, v);
      for (double t_seen : {seen.appear_seen_s, seen.disappear_seen_s}) {
        if (std::isnan(t_seen)) continue;
        ++r.changes_seen;
        seen_times[vehicles[v].id].push_back(t_seen);
        auto it = triggers.find(vehicles[v].id);
        if (it == triggers.end()) continue;
        for (const auto& [t, building] : it->second.samples) {
          if (t < t_seen || t > t_seen + options.detection_window_s) continue;
          if (!building) continue;
          latencies.push_back(t - t_seen);
          ++r.changes_detected;
          break;
        }
      }
    }
  }
  r.detection_latency_s = Summarize(latencies);
  for (const auto& [vehicle, t] : triggers) {
    for (double start : t.starts) {
      bool explained = false;
      for (double seen : seen_times[vehicle])
        explained |= start >= seen - 1.0 && start <= seen + options.trigger_window_s;
      r.false_triggers += !explained;
    }
  }
}

void ScoreLocalization(const std::vector<PoseSample>& poses, EvalReport& r) {
  std::vector<double> trans, rot;
  for (const PoseSample& p : poses) {
    const core::Pose2 e = core::Between(p.truth, p.estimated);
    trans.push_back(std::hypot(e.x_m, e.y_m));
    rot.push_back(std::abs(e.theta_rad) * kRadToDeg);
  }
  r.localization_error_m = Summarize(trans);
  r.localization_error_deg = Summarize(rot);
}

// A figure as report.json holds it: 6 significant digits (as the figure lines print it),
// null for NaN or infinity (a figure computed over nothing).
nlohmann::ordered_json Number(double v) {
  if (!std::isfinite(v)) return nullptr;
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.6g", v);
  return std::strtod(buf, nullptr);
}

// A count the run may not record: null then.
nlohmann::ordered_json Count(const std::optional<int64_t>& v) {
  return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr);
}

void AddStats(nlohmann::ordered_json& kv, const std::string& key, const SummaryStats& s) {
  kv[key + ".count"] = s.count;
  kv[key + ".median"] = Number(s.median);
  kv[key + ".p95"] = Number(s.p95);
  kv[key + ".max"] = Number(s.max);
}

// The scores of one kind of change (added or removed cells).
void AddKindScores(nlohmann::ordered_json& kv, const std::string& key, int64_t true_cells,
                   int64_t predicted_cells, double precision, double recall) {
  kv[key + ".true"] = true_cells;
  kv[key + ".predicted"] = predicted_cells;
  kv[key + ".precision"] = Number(precision);
  kv[key + ".recall"] = Number(recall);
}

}  // namespace

EvalReport Evaluate(const sim::World& world, const sim::ObservationLog& observations,
                    const RunRecord& run, const EvalOptions& options) {
  EvalReport r;
  r.scenario = world.scenario().name;
  r.pipeline = run.pipeline;
  r.resolution_m = world.geometry().resolution_m();
  r.changes = ScoreChanges(world, observations, run, options.scoring);
  ScoreAlignment(run.merges, r.resolution_m, r);
  ScoreDetection(world, observations, run, options, r);
  ScoreLocalization(run.poses, r);
  std::vector<double> merge_latency;
  for (const MergeRecord& m : run.merges)
    if (m.accepted) merge_latency.push_back(m.merged_s - m.closed_s);
  r.merge_latency_s = Summarize(merge_latency);
  r.merges = run.merges;
  return r;
}

std::string ReportJson(const EvalReport& r,
                       const std::vector<std::pair<std::string, std::string>>& extra) {
  nlohmann::ordered_json kv;
  kv["scenario"] = r.scenario;
  kv["pipeline"] = r.pipeline;
  const ChangeScores& c = r.changes;
  kv["changed_cells.precision"] = Number(c.precision);
  kv["changed_cells.recall"] = Number(c.recall);
  kv["changed_cells.f1"] = Number(c.f1);
  AddKindScores(kv, "changed_cells.added", c.true_added, c.predicted_added, c.added_precision,
                c.added_recall);
  AddKindScores(kv, "changed_cells.removed", c.true_removed, c.predicted_removed,
                c.removed_precision, c.removed_recall);
  kv["static_cells_erased"] = c.static_cells_erased;
  kv["actor_cells_mapped"] = c.actor_cells_mapped;
  kv["seen_free.drops"] = Count(c.seen_free_drops);
  kv["seen_free.drops_near_added"] = Count(c.seen_free_drops_near_added);
  kv["seen_free.added_missed"] = Count(c.added_missed_seen_free);
  kv["merges.accepted"] = r.merges_accepted;
  kv["merges.rejected"] = r.merges_rejected;
  AddStats(kv, "alignment.translation_m", r.align_translation_m);
  AddStats(kv, "alignment.translation_cells", r.align_translation_cells);
  AddStats(kv, "alignment.rotation_deg", r.align_rotation_deg);
  AddStats(kv, "alignment.anchor_translation_cells", r.anchor_translation_cells);
  AddStats(kv, "alignment.anchor_nees", r.anchor_nees);
  AddStats(kv, "tempmap.drift_m", r.tempmap_drift_m);
  AddStats(kv, "tempmap.drift_deg", r.tempmap_drift_deg);
  kv["detection.changes_seen"] = r.changes_seen;
  kv["detection.changes_detected"] = r.changes_detected;
  AddStats(kv, "detection.latency_s", r.detection_latency_s);
  kv["detection.false_triggers"] = r.false_triggers;
  AddStats(kv, "merge.latency_s", r.merge_latency_s);
  AddStats(kv, "localization.error_m", r.localization_error_m);
  AddStats(kv, "localization.error_deg", r.localization_error_deg);
  for (const auto& [key, value] : extra) kv[key] = nlohmann::ordered_json::parse(value);
  return kv.dump(2) + "\n";
}

std::string LineTable(const EvalReport& r) {
  std::ostringstream out;
  out << "| temporary map | temporary line id | static line id | distance difference (px) | "
         "angle difference (deg) |\n| --- | --- | --- | --- | --- |\n";
  int map_number = 0;
  for (const MergeRecord& m : r.merges) {
    if (!m.accepted) continue;
    ++map_number;
    for (const LineMatchRow& l : m.lines) {
      char row[160];
      std::snprintf(row, sizeof(row), "| %s#%d (Map%d) | %d | %d | %.6g | %.6g |\n",
                    m.vehicle_id.c_str(), m.tempmap_seq, map_number, l.temp_line_id,
                    l.static_line_id, l.distance_diff_px, l.angle_diff_deg);
      out << row;
    }
  }
  return out.str();
}

std::string ReportMarkdown(const EvalReport& r) {
  const ChangeScores& c = r.changes;
  char buf[2048];
  std::snprintf(
      buf, sizeof(buf),
      "# Evaluation: scenario %s, pipeline %s\n\n"
      "| figure | value |\n| --- | --- |\n"
      "| changed cells F1 (precision, recall) | %.3f (%.3f, %.3f) |\n"
      "| added cells: true / predicted | %lld / %lld |\n"
      "| removed cells: true / predicted | %lld / %lld |\n"
      "| static cells erased | %lld |\n| actor cells mapped | %lld |\n"
      "| merges accepted / rejected | %d / %d |\n"
      "| alignment translation median / p95 | %.3g / %.3g cells |\n"
      "| alignment rotation median / p95 | %.3g / %.3g deg |\n"
      "| changes seen / detected | %d / %d |\n"
      "| detection latency median | %.3g s |\n| false triggers | %d |\n"
      "| merge latency median | %.3g s |\n"
      "| localization error median / p95 | %.3g / %.3g m |\n",
      r.scenario.c_str(), r.pipeline.c_str(), c.f1, c.precision, c.recall, (long long)c.true_added,
      (long long)c.predicted_added, (long long)c.true_removed, (long long)c.predicted_removed,
      (long long)c.static_cells_erased, (long long)c.actor_cells_mapped, r.merges_accepted,
      r.merges_rejected, r.align_translation_cells.median, r.align_translation_cells.p95,
      r.align_rotation_deg.median, r.align_rotation_deg.p95, r.changes_seen, r.changes_detected,
      r.detection_latency_s.median, r.false_triggers, r.merge_latency_s.median,
      r.localization_error_m.median, r.localization_error_m.p95);
  return std::string(buf) + "\n## Matched lines (the paper's Tables 1/2)\n\n" + LineTable(r);
}

}  // namespace fleetmap::eval
