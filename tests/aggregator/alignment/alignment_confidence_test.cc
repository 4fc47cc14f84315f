#include "aggregator/alignment/alignment_confidence.h"

#include <gtest/gtest.h>

#include "aggregator/alignment/overlap_search.h"
#include "tests/aggregator/test_hall.h"

namespace fleetmap::aggregator {
namespace {

// Two well-matched lines, 10 m in all, a small correction: accepted.
AlignmentResult Good() {
  AlignmentResult a;
  LineMatch m;
  m.weight_m = 5.0;
  m.offset_m = 0.01;
  a.matches = {m, m};
  a.dx_m = 0.1;
  return a;
}

AlignmentConfidence Judge(const AlignmentResult& a, double before = 0.2, double after = 0.8) {
  return AssessAlignment(a, 0.05, before, after, {});
}

TEST(AlignmentConfidenceTest, AcceptsGoodEvidenceWithAScore) {
  const AlignmentConfidence c = Judge(Good());
  EXPECT_TRUE(c.accepted()) << c.explanation;
  EXPECT_NEAR(c.matched_length_m, 10.0, 1e-12);
  EXPECT_NEAR(c.residual_cells, 0.2, 1e-12);
  EXPECT_NEAR(c.overlap_gain, 0.6, 1e-12);
  EXPECT_GT(c.score, 0.5);
}

TEST(AlignmentConfidenceTest, EachReasonIsReportedWithWhatWasMeasured) {
  AlignmentResult a = Good();
  a.matches.resize(1);
  EXPECT_TRUE(Judge(a).accepted());  // one long wall (and its overlap) is enough
  a.matches[0].weight_m = 1.5;
  EXPECT_EQ(Judge(a).reason, RejectReason::kTooFewStaticLines);
  a.matches.clear();
  EXPECT_EQ(Judge(a).reason, RejectReason::kTooFewStaticLines);
  a = Good();
  for (LineMatch& m : a.matches) m.offset_m = 0.2;  // 4 cells
  EXPECT_EQ(Judge(a).reason, RejectReason::kLinesDisagree);
  a = Good();
  a.dx_m = 1.2;
  const AlignmentConfidence far = Judge(a);
  EXPECT_EQ(far.reason, RejectReason::kCorrectionTooLarge);
  EXPECT_NE(far.explanation.find("1.2"), std::string::npos) << far.explanation;
  EXPECT_EQ(far.score, 0.0);
  a = Good();
  a.shift_by_overlap = true;
  a.overlap.score = 0.8;
  a.overlap.lowest = 0.799;  // a flat overlap: the corridor says nothing along it
  EXPECT_EQ(Judge(a).reason, RejectReason::kAmbiguousShift);
  a.overlap.lowest = 0.5;
  a.overlap.step_best = 0.8;
  a.overlap.rival = 0.5;  // a single peak ...
  EXPECT_TRUE(Judge(a).accepted());
  a.overlap.at_edge = true;  // ... at the end of the range
  const AlignmentConfidence edge = Judge(a);
  EXPECT_EQ(edge.reason, RejectReason::kAmbiguousShift);
  EXPECT_NE(edge.explanation.find("end of its range"), std::string::npos) << edge.explanation;
  EXPECT_EQ(Judge(Good(), 0.8, 0.6).reason, RejectReason::kOverlapWorse);
  EXPECT_EQ(Judge(Good(), 0.1, 0.15).reason, RejectReason::kLowOverlap);
}

TEST(AlignmentConfidenceTest, AnotherPeakAlmostAsHighIsAmbiguous) {
  AlignmentResult a = Good();
  a.shift_by_overlap = true;
  a.overlap.score = a.overlap.step_best = 0.80;
  a.overlap.lowest = 0.70;
  a.overlap.rival = 0.79;  // rises 0.09 of the peak's 0.10: distinctness 0.1
  const AlignmentConfidence c = Judge(a);
  EXPECT_EQ(c.reason, RejectReason::kAmbiguousShift);
  EXPECT_NEAR(c.distinctness, 0.1, 1e-9);
  EXPECT_NE(c.explanation.find("another shift"), std::string::npos) << c.explanation;
  a.overlap.rival = 0.72;
  EXPECT_TRUE(Judge(a).accepted());
}

// The lines' correction where the cells found a rival: below the rival's score it is
// ambiguous, at or above it it stands, and a correction already rejected keeps its reason.
TEST(AlignmentConfidenceTest, LinesThatFitTheCellsWorseThanTheirRivalAreAmbiguous) {
  AlignmentConfidence lines;
  lines.score = 0.8;
  RejectBelowCellRival(0.75, 0.7, lines);
  EXPECT_TRUE(lines.accepted());
  EXPECT_EQ(lines.score, 0.8);
  RejectBelowCellRival(0.4, 0.7, lines);
  EXPECT_EQ(lines.reason, RejectReason::kAmbiguousShift);
  EXPECT_NE(lines.explanation.find("0.40"), std::string::npos) << lines.explanation;
  EXPECT_EQ(lines.score, 0.0);
  AlignmentConfidence worse;
  worse.reason = RejectReason::kOverlapWorse;
  RejectBelowCellRival(0.1, 0.7, worse);
  EXPECT_EQ(worse.reason, RejectReason::kOverlapWorse);
}

// Two rows of points 0.3 m apart, and a wall: each row fits it at its own shift, equally well.
TEST(OverlapSearchTest, TwoShiftsThatFitEquallyWellAreNotDistinct) {
  auto f = StaticMapFeatures::Compute(testing::HallMap());
  ASSERT_TRUE(f.ok());
  std::vector<Eigen::Vector2d> one_row, two_rows;
  for (double y = 2; y < 18; y += 0.05) {
    one_row.emplace_back(0.125 + 0.13, y);
    two_rows.emplace_back(0.125 + 0.13, y);
    two_rows.emplace_back(0.125 + 0.43, y);
  }
  const OverlapSearchOptions o;
  EXPECT_GT(SearchShift(*f, one_row, {1, 0}, o).Distinctness(), 0.9);
  const OverlapPeak both = SearchShift(*f, two_rows, {1, 0}, o);
  EXPECT_LT(both.Distinctness(), 0.1);
  EXPECT_GT(both.Prominence(), 0.3);  // the old test alone would have trusted it
}

TEST(OverlapSearchTest, FindsAShiftToAFractionOfACellAndSeesAFlatScore) {
  auto f = StaticMapFeatures::Compute(testing::HallMap());
  ASSERT_TRUE(f.ok());
  // Points on the west wall's surface and the pillar's west face, moved 0.13 m east.
  std::vector<Eigen::Vector2d> points;
  for (double y = 2; y < 18; y += 0.05) points.emplace_back(0.125 + 0.13, y);
  OverlapSearchOptions o;
  const OverlapPeak peak = SearchShift(*f, points, {1, 0}, o);
  EXPECT_NEAR(peak.shift_m, -0.13 + 0.25 * 0.05, 0.01);  // the ridge lies a quarter cell out
  EXPECT_GT(peak.Prominence(), 0.5);
  EXPECT_FALSE(peak.at_edge);
  // Along the wall nothing changes: a flat score.
  const OverlapPeak along = SearchShift(*f, points, {0, 1}, o);
  EXPECT_LT(along.Prominence(), 0.02);
}

}  // namespace
}  // namespace fleetmap::aggregator
