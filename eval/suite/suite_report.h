// The suite's report: a table per world (suite.md) and a picture of changed-cell F1 per world,
// grouped by style and ordered by resolution (suite.png).
#pragma once

#include <string>
#include <vector>

#include "core/result.h"
#include "eval/suite/suite_figures.h"

namespace fleetmap::eval::suite {

// The worlds grouped by style (generated), then the public maps, then the LivingLab; by
// resolution within a group.
std::vector<const WorldOutcome*> InReportOrder(const std::vector<WorldOutcome>& outcomes);

std::string SuiteMarkdown(const std::vector<WorldOutcome>& outcomes,
                          const std::vector<Figure>& figures);

core::Status WriteSuitePng(const std::vector<WorldOutcome>& outcomes, const std::string& path);

}  // namespace fleetmap::eval::suite
