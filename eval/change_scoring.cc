#include "eval/change_scoring.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fleetmap::eval {
namespace {

using Mask = std::vector<uint8_t>;

// Max filter of radius r (a square of side 2r + 1), separable.
Mask Dilate(const Mask& in, int w, int h, int r) {
  if (r <= 0) return in;
  Mask rows(in.size(), 0), out(in.size(), 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (in[size_t(y) * w + x])
        for (int dx = std::max(0, x - r); dx <= std::min(w - 1, x + r); ++dx)
          rows[size_t(y) * w + dx] = 1;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (rows[size_t(y) * w + x])
        for (int dy = std::max(0, y - r); dy <= std::min(h - 1, y + r); ++dy)
          out[size_t(dy) * w + x] = 1;
  return out;
}

struct Matched {
  int64_t predicted = 0, truth = 0, correct = 0, recalled = 0;
};

Matched Match(const Mask& predicted, const Mask& truth, int w, int h, int tolerance) {
  const Mask near_truth = Dilate(truth, w, h, tolerance);
  const Mask near_predicted = Dilate(predicted, w, h, tolerance);
  Matched m;
  for (size_t i = 0; i < predicted.size(); ++i) {
    m.predicted += predicted[i];
    m.truth += truth[i];
    m.correct += predicted[i] && near_truth[i];
    m.recalled += truth[i] && near_predicted[i];
  }
  return m;
}

// A share of nothing is undefined (NaN, null in report.json), never a perfect score.
double Ratio(int64_t num, int64_t den) {
  return den == 0 ? std::numeric_limits<double>::quiet_NaN() : double(num) / double(den);
}

// F1 of the matched predictions and truths. Undefined (NaN) when there was neither a truth
// nor a prediction; nothing predicted where there was a truth, or only false predictions, is 0.
double F1(int64_t correct, int64_t predicted, int64_t recalled, int64_t truth) {
  if (predicted == 0 && truth == 0) return std::numeric_limits<double>::quiet_NaN();
  const double p = predicted > 0 ? double(correct) / double(predicted) : 0.0;
  const double r = truth > 0 ? double(recalled) / double(truth) : 0.0;
  return p + r > 0 ? 2 * p * r / (p + r) : 0.0;
}

// Whether the vehicles' reports of candidates seen free dropped real objects.
void ScoreSeenFreeDrops(const RunRecord& run, const Mask& true_added, const Mask& final_occupied,
                        const core::GridGeometry& g, int tolerance, ChangeScores& s) {
  const Mask& dropped = run.dropped_seen_free;
  const int w = g.width(), h = g.height();
  const Mask near_added = Dilate(true_added, w, h, tolerance);
  const Mask near_dropped = NearSeenFreeDrops(run, g, tolerance);
  const Mask near_occupied = Dilate(final_occupied, w, h, tolerance);
  int64_t drops = 0, drops_near_added = 0, missed = 0;
  for (size_t i = 0; i < dropped.size(); ++i) {
    drops += dropped[i];
    drops_near_added += dropped[i] && near_added[i];
    missed += true_added[i] && !near_occupied[i] && near_dropped[i];
  }
  s.seen_free_drops = drops;
  s.seen_free_drops_near_added = drops_near_added;
  s.added_missed_seen_free = missed;
}

}  // namespace

std::vector<uint8_t> NearSeenFreeDrops(const RunRecord& run, const core::GridGeometry& geometry,
                                       int tolerance_cells) {
  if (run.dropped_seen_free.size() != static_cast<size_t>(geometry.num_cells())) return {};
  return Dilate(run.dropped_seen_free, geometry.width(), geometry.height(), tolerance_cells);
}

std::vector<uint8_t> ActorSweptCells(const sim::World& world, double sample_period_s) {
  const core::GridGeometry& g = world.geometry();
  Mask swept(static_cast<size_t>(g.num_cells()), 0);
  const auto& actors = world.scenario().actors;
  for (size_t a = 0; a < actors.size(); ++a) {
    const int r = static_cast<int>(std::ceil(actors[a].radius_m / g.resolution_m()));
    for (double t = 0; t <= world.scenario().duration_s; t += sample_period_s) {
      const Eigen::Vector2d p = world.ActorPositionAt(a, t);
      const core::CellIndex c = g.WorldToCell(p);
      for (int dy = -r; dy <= r; ++dy) {
        for (int dx = -r; dx <= r; ++dx) {
          const core::CellIndex n{c.x + dx, c.y + dy};
          if (!g.Contains(n)) continue;
          if ((g.CellCenter(n) - p).norm() <= actors[a].radius_m) swept[g.Index(n)] = 1;
        }
      }
    }
  }
  return swept;
}

ChangeScores ScoreChanges(const sim::World& world, const sim::ObservationLog& observations,
                          const RunRecord& run, const ScoringOptions& options) {
  const core::GridGeometry& g = world.geometry();
  const int w = g.width(), h = g.height();
  const size_t n = static_cast<size_t>(g.num_cells());
  const core::TriStateClassifier classify;
  Mask is_static(n), is_object(n), true_added(n, 0), true_removed(n, 0);
  Mask predicted_added(n, 0), predicted_removed(n, 0), final_occupied(n);
  ChangeScores s;
  for (size_t i = 0; i < n; ++i) {
    is_static[i] = classify(world.static_map().cells()[i]) == core::CellState::kOccupied;
    is_object[i] = world.object_raster()[i] > 0;
    final_occupied[i] = classify(run.final_map.cells()[i]) == core::CellState::kOccupied;
    if (const sim::CellObservations* o = observations.Cell(static_cast<int64_t>(i))) {
      const core::CellState last = o->LastState();
      true_added[i] = last == core::CellState::kOccupied && !is_static[i];
      true_removed[i] = o->ever_hit && last == core::CellState::kFree && !is_static[i];
    }
    if (is_static[i]) {
      s.static_cells_erased += !final_occupied[i];
      continue;
    }
    const bool ever = !run.ever_occupied.empty() && run.ever_occupied[i];
    predicted_added[i] = final_occupied[i];
    predicted_removed[i] = ever && !final_occupied[i];
  }
  const Matched added = Match(predicted_added, true_added, w, h, options.tolerance_cells);
  const Matched removed = Match(predicted_removed, true_removed, w, h, options.tolerance_cells);
  s.true_added = added.truth, s.true_removed = removed.truth;
  s.predicted_added = added.predicted, s.predicted_removed = removed.predicted;
  s.correct_added = added.correct, s.correct_removed = removed.correct;
  s.recalled_added = added.recalled, s.recalled_removed = removed.recalled;
  s.added_precision = Ratio(added.correct, added.predicted);
  s.added_recall = Ratio(added.recalled, added.truth);
  s.removed_precision = Ratio(removed.correct, removed.predicted);
  s.removed_recall = Ratio(removed.recalled, removed.truth);
  s.precision = Ratio(added.correct + removed.correct, added.predicted + removed.predicted);
  s.recall = Ratio(added.recalled + removed.recalled, added.truth + removed.truth);
  s.f1 = F1(added.correct + removed.correct, added.predicted + removed.predicted,
            added.recalled + removed.recalled, added.truth + removed.truth);

  // Actor cells: swept by an actor, away from walls and objects, and occupied at some point.
  const Mask swept = ActorSweptCells(world, options.actor_sample_period_s);
  Mask structure(n);
  for (size_t i = 0; i < n; ++i) structure[i] = is_static[i] || is_object[i];
  const Mask near_structure = Dilate(structure, w, h, options.tolerance_cells);
  for (size_t i = 0; i < n; ++i) {
    const bool occupied = final_occupied[i] || (!run.ever_occupied.empty() && run.ever_occupied[i]);
    s.actor_cells_mapped += swept[i] && !near_structure[i] && occupied;
  }
  if (run.dropped_seen_free.size() == n)
    ScoreSeenFreeDrops(run, true_added, final_occupied, g, options.tolerance_cells, s);
  return s;
}

}  // namespace fleetmap::eval
