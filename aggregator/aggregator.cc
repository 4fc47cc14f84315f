#include "aggregator/aggregator.h"

#include <algorithm>
#include <cmath>

#include "aggregator/alignment/alignment_steps.h"

namespace fleetmap::aggregator {
namespace {

// Centres of the set pixels, in the frame the grid's geometry is expressed in.
std::vector<Eigen::Vector2d> EdgePoints(const BinaryImage& edges, const core::GridGeometry& g) {
  const core::Pose2& o = g.origin();
  const double c = std::cos(o.theta_rad), s = std::sin(o.theta_rad), res = g.resolution_m();
  std::vector<Eigen::Vector2d> points;
  for (int y = 0; y < edges.height; ++y) {
    for (int x = 0; x < edges.width; ++x) {
      if (!edges.at(x, y)) continue;
      const double gx = (x + 0.5) * res, gy = (y + 0.5) * res;
      points.emplace_back(o.x_m + c * gx - s * gy, o.y_m + s * gx + c * gy);
    }
  }
  return points;
}

std::vector<LineReportRow> Rows(const AlignmentResult& a, double resolution_m) {
  std::vector<LineReportRow> rows;
  for (const LineMatch& m : a.matches) {
    rows.push_back({m.temp_index, m.static_index, std::abs(m.offset_m) / resolution_m,
                    m.angle_diff_rad * 180.0 / M_PI});
  }
  return rows;
}

// `second` where `first` was rejected, with both reasons in the text; the lines' reason where
// both were rejected (the one a vehicle acts on, see truth_tempmap_pipeline.h).
Assessment Either(Assessment first, Assessment second, bool cells_first) {
  const std::string first_name = cells_first ? "cells" : "lines";
  const std::string second_name = cells_first ? "lines" : "cells";
  std::string& text = second.confidence.explanation;
  if (second.confidence.accepted()) {
    text = "aligned by " + second_name + " (by " + first_name + ": " +
           first.confidence.explanation + ")";
    return second;
  }
  text = first_name + ": " + first.confidence.explanation + "; " + second_name + ": " + text;
  if (!cells_first) second.confidence.reason = first.confidence.reason;
  return second;
}

}  // namespace

core::Status AggregatorOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(placement.Validate());
  FLEETMAP_RETURN_IF_ERROR(temp_lines.Validate());
  FLEETMAP_RETURN_IF_ERROR(static_features.Validate());
  FLEETMAP_RETURN_IF_ERROR(alignment.Validate());
  FLEETMAP_RETURN_IF_ERROR(cell_alignment.Validate());
  FLEETMAP_RETURN_IF_ERROR(confidence.Validate());
  FLEETMAP_RETURN_IF_ERROR(anchor_gate.Validate());
  FLEETMAP_RETURN_IF_ERROR(merge.Validate());
  FLEETMAP_RETURN_IF_ERROR(store.Validate());
  return persistence.Validate();
}

core::Result<Aggregator> Aggregator::Create(core::OccupancyGrid static_map,
                                            const AggregatorOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  FLEETMAP_RETURN_IF_ERROR(static_map.geometry().Validate().WithContext("static map"));
  auto features = StaticMapFeatures::Compute(static_map, options.static_features);
  if (!features.ok()) return features.status();
  CurrentMapStore store(std::move(static_map), options.store);
  return Aggregator(options, std::move(features).value(), std::move(store));
}

core::Result<Aggregator> Aggregator::Open(core::OccupancyGrid static_map,
                                          const AggregatorOptions& options,
                                          const std::string& state_folder, RestoreReport* report) {
  auto aggregator = Create(std::move(static_map), options);
  if (!aggregator.ok()) return aggregator.status();
  auto persistence =
      MapPersistence::Open(state_folder, aggregator->store_, options.persistence, report);
  if (!persistence.ok()) return persistence.status();
  aggregator->persistence_.emplace(std::move(persistence).value());
  return aggregator;
}

Assessment Aggregator::ByLines(const AlignmentInput& in, const std::vector<Eigen::Vector2d>& points,
                               double before) const {
  Assessment l;
  l.alignment = Align(in, features_, options_.alignment);
  const double after =
      ExplainedFraction(features_, PlacePoints(points, l.alignment.correction * in.anchor));
  l.confidence = AssessAlignment(l.alignment, features_.geometry().resolution_m(), before, after,
                                 options_.confidence);
  return l;
}

Assessment Aggregator::ByCells(const AlignmentInput& in, const std::vector<Eigen::Vector2d>& points,
                               double before, CellAlignment* cells) const {
  Assessment c;
  *cells = AlignCells(features_, in.temp_points, in.anchor, options_.cell_alignment);
  const double after =
      ExplainedFraction(features_, PlacePoints(points, cells->correction * in.anchor));
  c.confidence = AssessCellAlignment(*cells, before, after, options_.confidence);
  c.alignment = WithCorrection(in, features_, options_.alignment, cells->correction);
  return c;
}

void Aggregator::KeepAnchorUnlessProven(const core::TempMap& map, const AlignmentInput& in,
                                        Assessment& a) const {
  AlignmentConfidence& c = a.confidence;
  const AnchorGateVerdict verdict =
      JudgeCorrection(in.anchor, map.anchor_covariance, a.alignment.correction, c.explained_before,
                      c.explained_after, options_.anchor_gate);
  c.anchor_mahalanobis_sq = verdict.mahalanobis_sq;
  if (verdict.take_correction) return;
  PlaceAtAnchor(in, verdict.explanation, a);
  if (c.explained_before < options_.confidence.min_explained_fraction) {
    c.reason = RejectReason::kLowOverlap;
    c.score = 0.0;
    char limit[96];
    std::snprintf(limit, sizeof(limit), "; there the explained fraction is %.3f < %.3f",
                  c.explained_before, options_.confidence.min_explained_fraction);
    c.explanation += limit;
  }
}

void Aggregator::StandWhereKnownWell(const core::TempMap& map, const AlignmentInput& in,
                                     Assessment& a) const {
  AlignmentConfidence& c = a.confidence;
  // A place the static map does not explain at the anchor is no place to stand.
  if (c.reason == RejectReason::kLowOverlap ||
      c.explained_before < options_.confidence.min_explained_fraction)
    return;
  const AnchorGateVerdict verdict =
      JudgeUnalignedAnchor(map.anchor_covariance, options_.anchor_gate);
  if (verdict.explanation.empty()) return;
  c.reason = RejectReason::kNone;
  c.anchor_mahalanobis_sq = 0.0;
  PlaceAtAnchor(in, verdict.explanation, a);
}

void Aggregator::PlaceAtAnchor(const AlignmentInput& in, const std::string& why,
                               Assessment& a) const {
  AlignmentConfidence& c = a.confidence;
  a.alignment = WithCorrection(in, features_, options_.alignment, core::Pose2());
  c.anchor_stands = true;
  c.explained_after = c.explained_before;
  c.overlap_gain = 0.0;
  c.explanation = why + (c.explanation.empty() ? "" : " (" + c.explanation + ")");
}

void Aggregator::CheckLinesAmongCellPeaks(const AlignmentInput& in, const CellAlignment& cells,
                                          Assessment& lines) const {
  const CellAlignmentOptions& o = options_.cell_alignment;
  // Only an accepted correction is judged, and only against a rival the cells found.
  if (!lines.confidence.accepted() || cells.at_edge ||
      cells.distinctness >= options_.confidence.min_distinctness)
    return;
  const double relative = cells.Relative(
      CellScoreAt(features_, in.temp_points, in.anchor, lines.alignment.correction, o));
  RejectBelowCellRival(relative, o.lines_min_relative_score, lines.confidence);
}

Assessment Aggregator::Assess(const core::TempMap& map) const {
  Assessment a;
  core::Status input = CheckTempMap(map, features_.geometry(), options_.placement);
  auto lines = input.ok() ? ExtractLineFeatures(map.grid, options_.temp_lines)
                          : core::Result<LineFeatures>(input);
  if (!lines.ok()) {
    a.reason = RejectReason::kInvalidTempMap;
    a.reason_text = lines.status().ToString();
    return a;
  }
  AlignmentInput in{lines->lines, EdgePoints(lines->edges, map.grid.geometry()), map.anchor_in_map};
  a.temp_lines = static_cast<int>(in.temp_lines.size());
  const auto points = Subsample(in.temp_points, options_.alignment.max_search_points);
  const double before = ExplainedFraction(features_, PlacePoints(points, in.anchor));
  const CellAlignmentUse use = options_.cell_alignment.use;
  const bool cells_first = use == CellAlignmentUse::kFirst;
  CellAlignment cells;
  Assessment tried =
      cells_first ? ByCells(in, points, before, &cells) : ByLines(in, points, before);
  if (!tried.confidence.accepted() && use != CellAlignmentUse::kOff) {
    Assessment second =
        cells_first ? ByLines(in, points, before) : ByCells(in, points, before, &cells);
    if (cells_first) CheckLinesAmongCellPeaks(in, cells, second);
    tried = Either(std::move(tried), std::move(second), cells_first);
  } else if (cells_first) {
    tried.confidence.explanation = "aligned by cells";
  }
  if (tried.confidence.accepted())
    KeepAnchorUnlessProven(map, in, tried);
  else
    StandWhereKnownWell(map, in, tried);
  a.alignment = std::move(tried.alignment);
  a.confidence = std::move(tried.confidence);
  a.reason = a.confidence.reason;
  a.reason_text = a.confidence.explanation;
  return a;
}

MergeReport Aggregator::Rejected(const core::TempMap& map, const Assessment& assessment) {
  MergeReport r;
  r.vehicle_id = map.vehicle_id;
  r.tempmap_sequence = map.sequence;
  r.reason = assessment.reason;
  r.reason_text = assessment.reason_text;
  r.alignment = assessment.alignment;
  r.confidence = assessment.confidence;
  r.version = store_.version();
  ++stats_.rejected;
  ++stats_.rejected_by_reason[static_cast<size_t>(assessment.reason)];
  return r;
}

core::Result<MergeReport> Aggregator::Commit(const core::TempMap& map, const Assessment& assessment,
                                             double now_s) {
  if (!assessment.accepted()) return Rejected(map, assessment);
  const core::Pose2& correction = assessment.alignment.correction;
  const PlacedEvidence evidence = PlaceEvidence(map, correction, store_.static_map().geometry());
  const MergeInputs inputs{&addable_,
                           &wall_distance_,
                           &store_.semi_static(),
                           &store_.candidates(),
                           &store_.candidate_mask(),
                           &store_.changed_at_s()};
  const MergePlan plan = PlanMerge(evidence, {map.start_s, map.end_s}, inputs, options_.merge);
  MergeCommit commit{store_.version() + 1,
                     {map.vehicle_id, map.sequence, map.start_s, map.end_s, now_s},
                     correction,
                     plan.changes};
  FLEETMAP_RETURN_IF_ERROR(store_.Check(commit));
  if (persistence_) FLEETMAP_RETURN_IF_ERROR(persistence_->Record(commit));
  MergeReport r;
  FLEETMAP_ASSIGN_OR_RETURN(r.delta, store_.Apply(std::move(commit)));
  r.vehicle_id = map.vehicle_id;
  r.tempmap_sequence = map.sequence;
  r.accepted = true;
  r.reason_text = assessment.reason_text;  // how it was aligned, where not by lines alone
  r.correction = correction;
  r.alignment = assessment.alignment;
  r.confidence = assessment.confidence;
  r.lines = Rows(assessment.alignment, store_.static_map().geometry().resolution_m());
  r.cells_added = plan.added;
  r.cells_removed = plan.removed;
  r.candidates_new = plan.candidates;
  r.candidates_dropped = plan.dropped;
  r.version = store_.version();
  ++stats_.accepted;
  if (persistence_ && persistence_->SnapshotDue()) {
    const core::Status s = persistence_->Snapshot(store_);
    if (!s.ok()) r.warning = "merge journaled, snapshot failed: " + s.ToString();
  }
  return r;
}

core::Result<MergeReport> Aggregator::Submit(const core::TempMap& map, double now_s) {
  return Commit(map, Assess(map), now_s);
}

core::Result<std::vector<int64_t>> Aggregator::DropCandidatesSeenFree(const std::string& vehicle_id,
                                                                      const SeenFreeReport& report,
                                                                      double now_s) {
  return CommitReport(vehicle_id, {report.first_pass_s, report.last_pass_s},
                      PlanCandidateDrops(report, store_.candidates()), now_s);
}

core::Result<std::vector<int64_t>> Aggregator::ConfirmCandidatesHeld(const std::string& vehicle_id,
                                                                     const HeldReport& report,
                                                                     double now_s) {
  std::vector<CellChange> adds =
      PlanHeldConfirmations(report, store_.candidates(), options_.merge, &wall_distance_,
                            store_.static_map().geometry().resolution_m());
  if (adds.empty()) return std::vector<int64_t>{};
  const auto since = std::min_element(report.since_s.begin(), report.since_s.end());
  const auto until = std::max_element(report.until_s.begin(), report.until_s.end());
  return CommitReport(vehicle_id, {*since, *until}, std::move(adds), now_s);
}

core::Result<std::vector<int64_t>> Aggregator::CommitReport(const std::string& vehicle_id,
                                                            const TimeSpan& span,
                                                            std::vector<CellChange> changes,
                                                            double now_s) {
  std::vector<int64_t> cells;
  if (changes.empty()) return cells;
  cells.reserve(changes.size());
  for (const CellChange& c : changes) cells.push_back(c.cell);
  MergeCommit commit{store_.version() + 1,
                     {vehicle_id, kSeenFreeSequence, span.start_s, span.end_s, now_s},
                     core::Pose2(),
                     std::move(changes)};
  FLEETMAP_RETURN_IF_ERROR(store_.Check(commit));
  if (persistence_) FLEETMAP_RETURN_IF_ERROR(persistence_->Record(commit));
  FLEETMAP_RETURN_IF_ERROR(store_.Apply(std::move(commit)).status());
  return cells;
}

core::Status Aggregator::WriteSnapshot() {
  if (!persistence_) return core::FailedPrecondition("the aggregator has no persistence folder");
  return persistence_->Snapshot(store_);
}

}  // namespace fleetmap::aggregator
