#include "eval/suite/suite_figures.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>

namespace fleetmap::eval::suite {
namespace {

using ::testing::HasSubstr;

WorldScore Score(double f1, int64_t actors = 0, int accepted = 9, int rejected = 1) {
  WorldScore s;
  s.changed_f1 = f1;
  s.added_recall = f1;
  s.removed_recall = NAN;  // nothing taken away: in no aggregate of removed recall
  s.actor_mapped = actors;
  s.align_trans_p95_cells = 1.0;
  s.merges_accepted = accepted;
  s.merges_rejected = rejected;
  return s;
}

WorldOutcome World(const std::string& name, std::optional<WorldScore> agents,
                   WorldSource source = WorldSource::kGenerated) {
  WorldOutcome o;
  o.world.name = name;
  o.world.source = source;
  o.agents = agents;
  return o;
}

std::map<std::string, double> ByName(const std::vector<Figure>& figures) {
  std::map<std::string, double> m;
  for (const Figure& f : figures) m[f.name] = f.value;
  return m;
}

TEST(SuiteFiguresTest, QuantilesInterpolateAndSkipWhatIsNotANumber) {
  EXPECT_DOUBLE_EQ(Quantile({3, 1, 2, NAN}, 0.5), 2.0);
  EXPECT_DOUBLE_EQ(Quantile({1, 2, 3, 4}, 0.5), 2.5);
  EXPECT_DOUBLE_EQ(Quantile({1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}, 0.1), 2.0);
  EXPECT_DOUBLE_EQ(Quantile({5, 1}, 0.0), 1.0);
  EXPECT_TRUE(std::isnan(Quantile({NAN}, 0.5)));
}

TEST(SuiteFiguresTest, UnusableWorldsAndTheLivingLabAreInNoAggregate) {
  WorldOutcome unusable = World("blank", std::nullopt);
  unusable.unusable = "nothing in the map is observed";
  const std::vector<WorldOutcome> outcomes = {
      World("a", Score(0.9, 10)), World("b", Score(0.7, 0, 3, 1)), unusable,
      World("livinglab", Score(0.99), WorldSource::kLivingLab)};
  auto figures = SuiteFigures(outcomes);
  ASSERT_TRUE(figures.ok()) << figures.status().ToString();
  auto f = ByName(*figures);
  EXPECT_EQ(f["suite.worlds"], 2);
  EXPECT_EQ(f["suite.unusable"], 1);
  EXPECT_DOUBLE_EQ(f["suite.changed_f1.median"], 0.8);
  EXPECT_DOUBLE_EQ(f["suite.changed_f1.min"], 0.7);
  EXPECT_DOUBLE_EQ(f["suite.actor_mapped.max"], 10);
  EXPECT_DOUBLE_EQ(f["suite.rejected_share.max"], 0.25);
  EXPECT_DOUBLE_EQ(f["suite.livinglab.changed_f1"], 0.99);
  EXPECT_DOUBLE_EQ(f["suite.world.b.changed_f1"], 0.7);
  // Removed recall was measured nowhere: no figure rather than a 0 or a 1.
  EXPECT_EQ(f.count("suite.removed_recall.median"), 0u);
  EXPECT_EQ(f.count("suite.world.blank.changed_f1"), 0u);
  EXPECT_EQ(f.count("suite.truthmaps.worlds"), 0u);  // not run
}

TEST(SuiteFiguresTest, ASuiteWithoutAnyScoredWorldIsAnError) {
  WorldOutcome unusable = World("blank", std::nullopt);
  unusable.unusable = "the map has no cells";
  auto figures = SuiteFigures({unusable, World("livinglab", Score(1.0), WorldSource::kLivingLab)});
  ASSERT_FALSE(figures.ok());
  EXPECT_THAT(figures.status().message(), HasSubstr("no world has a score"));
}

// The aggregator alone, its vehicles left out (--pipelines truthmaps): its figures, none of
// the system's.
TEST(SuiteFiguresTest, ASuiteOfTheTruthmapsPipelineAloneHasItsFigures) {
  WorldOutcome a = World("a", std::nullopt), b = World("b", std::nullopt);
  a.truthmaps = Score(0.9);
  b.truthmaps = Score(0.7);
  auto figures = SuiteFigures({a, b});
  ASSERT_TRUE(figures.ok()) << figures.status().ToString();
  auto f = ByName(*figures);
  EXPECT_EQ(f["suite.truthmaps.worlds"], 2);
  EXPECT_DOUBLE_EQ(f["suite.truthmaps.changed_f1.median"], 0.8);
  EXPECT_EQ(f.count("suite.worlds"), 0u);
  EXPECT_EQ(f.count("suite.changed_f1.median"), 0u);
  EXPECT_DOUBLE_EQ(f["suite.world.a.truthmaps.changed_f1"], 0.9);
}

TEST(SuiteFiguresTest, FigureLinesAreNameValueUnit) {
  EXPECT_EQ(FigureLines({{"suite.worlds", 41, "worlds"}, {"suite.changed_f1.min", 0.5, "ratio"}}),
            "suite.worlds 41 worlds\nsuite.changed_f1.min 0.5 ratio\n");
}

}  // namespace
}  // namespace fleetmap::eval::suite
