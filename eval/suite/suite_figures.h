// The suite's figures: per world, and over all usable worlds (median, min, p10, max), as
// `name value unit` lines (docs/world_suite.md lists them). A world that could not be used is
// reported by name and reason and is in no aggregate; a figure over no world is an error.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/result.h"
#include "eval/suite/suite_plan.h"
#include "eval/suite/world_preparation.h"
#include "eval/suite/world_score.h"

namespace fleetmap::eval::suite {

struct WorldOutcome {
  SuiteWorld world;
  PreparedWorld prepared;
  std::string unusable;  // why the world could not be used; empty: it was
  std::optional<WorldScore> agents, truthmaps;
  std::string agents_error, truthmaps_error;  // a run that failed: its reason
};

struct Figure {
  std::string name;
  double value;
  std::string unit;
};

// Per world: suite.world.<name>.<figure>; in aggregate: suite.<figure> (the agents pipeline),
// suite.truthmaps.<figure>, suite.worlds, suite.unusable, suite.livinglab.changed_f1. The
// LivingLab is reported beside the suite, in no aggregate. FailedPrecondition when no world
// has a score.
core::Result<std::vector<Figure>> SuiteFigures(const std::vector<WorldOutcome>& outcomes);

std::string FigureLines(const std::vector<Figure>& figures);

// The q-quantile (0..1, linear between order statistics) of the finite values; NaN when
// none is finite.
double Quantile(std::vector<double> values, double q);

}  // namespace fleetmap::eval::suite
