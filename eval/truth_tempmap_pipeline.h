// The truthmaps pipeline: the aggregator fed with the temporary maps a perfect vehicle would
// build. From the simulator's scans at their TRUE poses, each vehicle starts a temporary map
// when its scan disagrees with the current map (ScanDisagreement), inserts its scans in its
// start frame T (core::InsertScan) into a bounded grid at the static map's resolution, and
// closes it after a bounded time or distance, or once the disagreement has stopped. The
// anchor is the true start pose perturbed by a seeded random error (uniform magnitude up to
// anchor_error_max_m, uniform direction, uniform rotation within +-anchor_error_max_rad), and
// the aggregator aligns and merges it. So the evaluation scores the aggregator alone: its
// alignment against the truth, and the map it makes. A map rejected because it holds too
// little of the building is extended and sent again (max_extensions).
#pragma once

#include <memory>

#include "aggregator/aggregator.h"
#include "core/map/scan_inserter.h"
#include "eval/pipeline.h"
#include "eval/scan_disagreement.h"
#include "vehicle_agent/candidate_watch.h"

namespace fleetmap::eval {

struct TruthTempMapOptions {
  aggregator::AggregatorOptions aggregator;  // alignment mode among them
  DisagreementOptions trigger;
  core::ScanInsertOptions insert;
  core::MovingCellOptions moving;  // what moved while a map was built is reported free
  double grid_size_m = 20.0;       // side of the square temporary grid
  // The grid's centre lies this far from the vehicle towards the disagreement (at most as
  // far as the disagreement), so what started the map is inside it.
  double grid_lead_m = 8.0;
  double max_duration_s = 8.0;  // a temporary map closes after this long ...
  double max_distance_m = 4.0;  // ... or once the vehicle drove this far ...
  double quiet_close_s = 3.0;   // ... or when no disagreement was seen for this long,
  double min_duration_s = 2.0;  //     but not before this
  // A map rejected for too few static lines or an ambiguous shift is kept and extended (its
  // time and distance limits grow by their own size) up to this many times, as a vehicle
  // told so would do: it then holds more of the building. Other rejections start afresh.
  int max_extensions = 2;
  double anchor_error_max_m = 0.3;
  double anchor_error_max_rad = 3.0 * M_PI / 180;
  uint32_t seed = 0;                 // added to the scenario's seed for the anchor errors
  double divergence_period_s = 0.2;  // how often a DivergenceSample is recorded per vehicle
  // The vehicles report the candidates their scans saw free, as agents do.
  vehicle_agent::CandidateWatchOptions candidate_watch;
  core::Status Validate() const;
};

// The aggregator's defaults expect anchors from a localized vehicle (a few centimetres off).
// This widens what must cover the anchor's error (the correction limits and the first search
// along the lines) to anchors off by up to `max_m` and `max_rad`, never narrowing a setting.
void CoverAnchorErrors(double max_m, double max_rad, aggregator::AggregatorOptions& options);

// `world` outlives the pipeline. InvalidArgument for bad options, or the aggregator's error.
// The aggregator runs with options.aggregator widened by CoverAnchorErrors for the pipeline's
// own anchor errors.
core::Result<std::unique_ptr<Pipeline>> MakeTruthTempMapPipeline(
    const sim::World& world, const TruthTempMapOptions& options);

}  // namespace fleetmap::eval
