// Scores a run against the simulator's ground truth and writes report.json. The keys of
// report.json are stable (docs/evaluation.md): our figures and every later comparison read them.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "eval/change_scoring.h"
#include "eval/summary_stats.h"

namespace fleetmap::eval {

struct EvalOptions {
  ScoringOptions scoring;
  // A trigger (a temporary map started) counts as true when the vehicle first saw a change
  // at most this long before it (or up to 1 s after it).
  double trigger_window_s = 30.0;
  // A change counts as detected when the vehicle builds a temporary map within this long
  // after first seeing it; the latency is the time until the first such sample.
  double detection_window_s = 10.0;
};

struct EvalReport {
  std::string scenario;
  std::string pipeline;
  double resolution_m = 0.05;
  ChangeScores changes;
  int merges_accepted = 0;
  int merges_rejected = 0;
  SummaryStats align_translation_m, align_translation_cells, align_rotation_deg;
  // The same merges' placement by their anchors alone (no correction), cells.
  SummaryStats anchor_translation_cells;
  // MergeRecord::anchor_nees over every map that sent a covariance (accepted or not).
  SummaryStats anchor_nees;
  // How far the vehicles' builders drifted within each map, accepted or not (count 0 where
  // the run does not know).
  SummaryStats tempmap_drift_m, tempmap_drift_deg;
  int changes_seen = 0;      // (object, vehicle) pairs where the vehicle saw the change
  int changes_detected = 0;  // ... and d(t) > 0 followed within the trigger window
  SummaryStats detection_latency_s;
  int false_triggers = 0;
  SummaryStats merge_latency_s;  // temporary map closed -> change in the current map
  SummaryStats localization_error_m, localization_error_deg;
  std::vector<MergeRecord> merges;  // for the line tables
};

EvalReport Evaluate(const sim::World& world, const sim::ObservationLog& observations,
                    const RunRecord& run, const EvalOptions& options = {});

// report.json text: flat dotted keys ("changed_cells.f1", ...) with numbers (null for NaN),
// then the `extra` keys, each with its value as JSON text (a number or null).
std::string ReportJson(const EvalReport& report,
                       const std::vector<std::pair<std::string, std::string>>& extra = {});
// The paper's Tables 1/2: one row per matched line of every accepted merge.
std::string LineTable(const EvalReport& report);
// A short human-readable summary (report.md).
std::string ReportMarkdown(const EvalReport& report);

}  // namespace fleetmap::eval
