#include "eval/suite/world_score.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <fstream>

namespace fleetmap::eval::suite {
namespace {

using ::testing::HasSubstr;

std::string Write(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name + std::to_string(getpid()) + ".json";
  std::ofstream(path) << text;
  return path;
}

constexpr const char* kReport = R"({
  "scenario": "g_office_1", "changed_cells.f1": 0.8, "changed_cells.added.recall": 0.9,
  "changed_cells.removed.recall": null, "static_cells_erased": 0, "actor_cells_mapped": 12,
  "alignment.translation_cells.p95": 1.25, "merges.accepted": 15, "merges.rejected": 5,
  "changed_cells.added.true": 300, "changed_cells.removed.true": 0
})";

TEST(WorldScoreTest, ReadsTheFiguresOfAReport) {
  auto s = ReadWorldScore(Write("report_ok", kReport));
  ASSERT_TRUE(s.ok()) << s.status().ToString();
  EXPECT_DOUBLE_EQ(s->changed_f1, 0.8);
  EXPECT_TRUE(std::isnan(s->removed_recall));
  EXPECT_EQ(s->actor_mapped, 12);
  EXPECT_DOUBLE_EQ(s->align_trans_p95_cells, 1.25);
  EXPECT_DOUBLE_EQ(s->RejectedShare(), 0.25);
}

// The anchor's error is read where a report gives it; a report without it has none (NaN, left
// out of the aggregate), not 0.
TEST(WorldScoreTest, TheAnchorsErrorIsReadWhereGiven) {
  auto without = ReadWorldScore(Write("report_no_anchor", kReport));
  ASSERT_TRUE(without.ok());
  EXPECT_TRUE(std::isnan(without->anchor_trans_p95_cells));
  std::string report = kReport;
  report.insert(report.find("\"merges.accepted\""),
                "\"alignment.anchor_translation_cells.p95\": 2.5, ");
  auto with = ReadWorldScore(Write("report_anchor", report));
  ASSERT_TRUE(with.ok()) << with.status().ToString();
  EXPECT_DOUBLE_EQ(with->anchor_trans_p95_cells, 2.5);
}

// The added cells lost to candidates dropped as seen free, as a share of the added cells; a
// run that does not record drops (null) has no share, not 0.
TEST(WorldScoreTest, TheAddedCellsLostToSeenFreeDropsAreAShareOfTheAdded) {
  EXPECT_TRUE(std::isnan(ReadWorldScore(Write("report_no_drops", kReport))->added_lost_seen_free));
  std::string report = kReport;
  const size_t at = report.find("\"merges.accepted\"");
  report.insert(at, "\"seen_free.added_missed\": null, ");
  EXPECT_TRUE(std::isnan(ReadWorldScore(Write("report_null_drops", report))->added_lost_seen_free));
  report = kReport;
  report.insert(at, "\"seen_free.added_missed\": 30, ");
  auto s = ReadWorldScore(Write("report_drops", report));
  ASSERT_TRUE(s.ok()) << s.status().ToString();
  EXPECT_DOUBLE_EQ(s->added_lost_seen_free, 0.1);  // 30 of 300
}

TEST(WorldScoreTest, TheBuildersDriftIsReadWhereGiven) {
  auto without = ReadWorldScore(Write("report_no_drift", kReport));
  ASSERT_TRUE(without.ok()) << without.status().ToString();
  EXPECT_TRUE(std::isnan(without->tempmap_drift_p95_m));
  EXPECT_TRUE(std::isnan(without->tempmap_drift_p95_deg));
  std::string report = kReport;
  report.insert(report.find("\"merges.accepted\""),
                "\"tempmap.drift_m.p95\": 0.058, \"tempmap.drift_deg.p95\": 0.32, ");
  auto s = ReadWorldScore(Write("report_drift", report));
  ASSERT_TRUE(s.ok()) << s.status().ToString();
  EXPECT_DOUBLE_EQ(s->tempmap_drift_p95_m, 0.058);
  EXPECT_DOUBLE_EQ(s->tempmap_drift_p95_deg, 0.32);
}

// How honest the anchors' covariance was, and how well the vehicles were localized: read where
// a report gives them (agents); a run without them (truthmaps) has none, not 0.
TEST(WorldScoreTest, TheAnchorsNeesAndTheLocalizationErrorAreReadWhereGiven) {
  auto without = ReadWorldScore(Write("report_no_nees", kReport));
  ASSERT_TRUE(without.ok()) << without.status().ToString();
  EXPECT_TRUE(std::isnan(without->anchor_nees_p95));
  EXPECT_TRUE(std::isnan(without->localization_p95_m));
  std::string report = kReport;
  report.insert(report.find("\"merges.accepted\""),
                "\"alignment.anchor_nees.p95\": 428.5, \"localization.error_m.p95\": 0.09, ");
  auto s = ReadWorldScore(Write("report_nees", report));
  ASSERT_TRUE(s.ok()) << s.status().ToString();
  EXPECT_DOUBLE_EQ(s->anchor_nees_p95, 428.5);
  EXPECT_DOUBLE_EQ(s->localization_p95_m, 0.09);
}

TEST(WorldScoreTest, AReportWithoutAKeyOrNotJsonIsDataLoss) {
  std::string report = kReport;
  report.replace(report.find("\"actor_cells_mapped\""), 20, "\"actors\"");
  auto missing = ReadWorldScore(Write("report_missing", report));
  ASSERT_FALSE(missing.ok());
  EXPECT_THAT(missing.status().message(), HasSubstr("actor_cells_mapped"));
  EXPECT_EQ(ReadWorldScore(Write("report_torn", "{\"changed_cells.f1\": 0.")).status().code(),
            core::StatusCode::kDataLoss);
  EXPECT_FALSE(ReadWorldScore(::testing::TempDir() + "no_such_report.json").ok());
}

TEST(WorldScoreTest, AWorldWhereNothingChangedHasNoScore) {
  std::string report = kReport;
  report.replace(report.find("\"changed_cells.added.true\": 300"), 31,
                 "\"changed_cells.added.true\": 0");
  auto s = ReadWorldScore(Write("report_nothing", report));
  ASSERT_FALSE(s.ok());
  EXPECT_THAT(s.status().message(), HasSubstr("no cell of the world changed"));
}

TEST(WorldScoreTest, NoMergeMeansNoRejectedShare) {
  WorldScore s;
  EXPECT_TRUE(std::isnan(s.RejectedShare()));
}

}  // namespace
}  // namespace fleetmap::eval::suite
