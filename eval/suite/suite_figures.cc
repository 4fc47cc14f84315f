#include "eval/suite/suite_figures.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>

namespace fleetmap::eval::suite {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool InAggregate(const WorldOutcome& o) {
  return o.unusable.empty() && o.world.source != WorldSource::kLivingLab;
}

using Metric = std::function<double(const WorldScore&)>;

struct Aggregate {
  const char* figure;
  Metric metric;
  std::vector<const char*> statistics;  // "median", "min", "p10", "max"
  const char* unit;
};

const std::vector<Aggregate>& Aggregates() {
  static const std::vector<Aggregate> kAggregates = {
      {"changed_f1",
       [](const WorldScore& s) { return s.changed_f1; },
       {"median", "min", "p10"},
       "ratio"},
      {"added_recall",
       [](const WorldScore& s) { return s.added_recall; },
       {"median", "min"},
       "ratio"},
      {"added_lost_seen_free",
       [](const WorldScore& s) { return s.added_lost_seen_free; },
       {"median", "max"},
       "ratio"},
      {"removed_recall",
       [](const WorldScore& s) { return s.removed_recall; },
       {"median", "min"},
       "ratio"},
      {"static_erased",
       [](const WorldScore& s) { return double(s.static_erased); },
       {"max"},
       "cells"},
      {"actor_mapped",
       [](const WorldScore& s) { return double(s.actor_mapped); },
       {"median", "max"},
       "cells"},
      {"align_trans_p95_cells",
       [](const WorldScore& s) { return s.align_trans_p95_cells; },
       {"median", "max"},
       "cells"},
      {"anchor_trans_p95_cells",
       [](const WorldScore& s) { return s.anchor_trans_p95_cells; },
       {"median", "max"},
       "cells"},
      {"localization_p95_m",
       [](const WorldScore& s) { return s.localization_p95_m; },
       {"median", "max"},
       "m"},
      {"anchor_nees_p95",
       [](const WorldScore& s) { return s.anchor_nees_p95; },
       {"median", "max"},
       "ratio"},
      {"tempmap_drift_p95_m",
       [](const WorldScore& s) { return s.tempmap_drift_p95_m; },
       {"median", "max"},
       "m"},
      {"tempmap_drift_p95_deg",
       [](const WorldScore& s) { return s.tempmap_drift_p95_deg; },
       {"median", "max"},
       "deg"},
      {"rejected_share",
       [](const WorldScore& s) { return s.RejectedShare(); },
       {"median", "max"},
       "ratio"},
  };
  return kAggregates;
}

double Statistic(const std::vector<double>& values, const std::string& which) {
  if (which == "median") return Quantile(values, 0.5);
  if (which == "p10") return Quantile(values, 0.1);
  if (which == "min") return Quantile(values, 0.0);
  return Quantile(values, 1.0);
}

void PerWorld(const WorldOutcome& o, std::vector<Figure>& out) {
  const auto add = [&](const char* pipeline, const std::optional<WorldScore>& s) {
    if (!s) return;
    const std::string prefix = "suite.world." + o.world.name + pipeline;
    for (const Aggregate& a : Aggregates()) {
      const double v = a.metric(*s);
      if (std::isfinite(v)) out.push_back({prefix + "." + a.figure, v, a.unit});
    }
  };
  add("", o.agents);
  add(".truthmaps", o.truthmaps);
}

// `prefix`.<figure>.<statistic> over the worlds that have a score of `pipeline`.
core::Status AddAggregates(const std::vector<WorldOutcome>& outcomes, const std::string& prefix,
                           std::optional<WorldScore> WorldOutcome::*pipeline,
                           std::vector<Figure>& out) {
  int scored = 0;
  for (const WorldOutcome& o : outcomes) scored += InAggregate(o) && (o.*pipeline).has_value();
  if (scored == 0) return core::FailedPrecondition(prefix + ": no world has a score");
  out.push_back({prefix + ".worlds", double(scored), "worlds"});
  for (const Aggregate& a : Aggregates()) {
    std::vector<double> values;
    for (const WorldOutcome& o : outcomes)
      if (InAggregate(o) && (o.*pipeline)) {
        const double v = a.metric(*(o.*pipeline));
        if (std::isfinite(v)) values.push_back(v);
      }
    if (values.empty()) continue;  // e.g. no world with an accepted merge: said by its absence
    for (const char* statistic : a.statistics)
      out.push_back(
          {prefix + "." + a.figure + "." + statistic, Statistic(values, statistic), a.unit});
  }
  return core::OkStatus();
}

}  // namespace

double Quantile(std::vector<double> values, double q) {
  values.erase(
      std::remove_if(values.begin(), values.end(), [](double v) { return !std::isfinite(v); }),
      values.end());
  if (values.empty()) return kNaN;
  std::sort(values.begin(), values.end());
  const double at = std::clamp(q, 0.0, 1.0) * double(values.size() - 1);
  const size_t below = static_cast<size_t>(std::floor(at));
  const size_t above = std::min(below + 1, values.size() - 1);
  return values[below] + (values[above] - values[below]) * (at - double(below));
}

core::Result<std::vector<Figure>> SuiteFigures(const std::vector<WorldOutcome>& outcomes) {
  std::vector<Figure> out;
  for (const WorldOutcome& o : outcomes) PerWorld(o, out);
  // Either pipeline may have been left out (--pipelines); a suite where neither scored a
  // world is an error, never figures over nothing.
  const core::Status agents = AddAggregates(outcomes, "suite", &WorldOutcome::agents, out);
  const core::Status truthmaps =
      AddAggregates(outcomes, "suite.truthmaps", &WorldOutcome::truthmaps, out);
  for (const core::Status& s : {agents, truthmaps})
    if (!s.ok() && s.code() != core::StatusCode::kFailedPrecondition) return s;
  if (!agents.ok() && !truthmaps.ok()) return agents;
  int unusable = 0;
  for (const WorldOutcome& o : outcomes) unusable += !o.unusable.empty();
  out.push_back({"suite.unusable", double(unusable), "worlds"});
  for (const WorldOutcome& o : outcomes)
    if (o.world.source == WorldSource::kLivingLab && o.agents)
      out.push_back({"suite.livinglab.changed_f1", o.agents->changed_f1, "ratio"});
  return out;
}

std::string FigureLines(const std::vector<Figure>& figures) {
  std::ostringstream text;
  text.precision(6);
  for (const Figure& f : figures) text << f.name << ' ' << f.value << ' ' << f.unit << '\n';
  return text.str();
}

}  // namespace fleetmap::eval::suite
