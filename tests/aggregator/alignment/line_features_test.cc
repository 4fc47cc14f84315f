#include "aggregator/alignment/line_features.h"

#include <gtest/gtest.h>

#include <cmath>

#include "aggregator/alignment/dominant_directions.h"
#include "aggregator/alignment/hough_lines.h"
#include "aggregator/alignment/line_consolidation.h"
#include "aggregator/alignment/static_features.h"
#include "tests/aggregator/test_hall.h"

namespace fleetmap::aggregator {
namespace {

TEST(LineSegmentTest, HesseNormalFormOfAxisAndDiagonalLines) {
  const LineSegment horizontal{{0, 2}, {5, 2}};
  EXPECT_NEAR(horizontal.hesse().theta_rad, M_PI / 2, 1e-12);
  EXPECT_NEAR(horizontal.hesse().r, 2.0, 1e-12);
  // The same line drawn the other way round has the same Hesse form (theta in [0, pi)).
  const LineSegment reversed{{5, 2}, {0, 2}};
  EXPECT_NEAR(reversed.hesse().theta_rad, M_PI / 2, 1e-12);
  EXPECT_NEAR(reversed.hesse().r, 2.0, 1e-12);
  const LineSegment diagonal{{1, 0}, {0, 1}};  // x + y = 1
  EXPECT_NEAR(diagonal.hesse().theta_rad, M_PI / 4, 1e-12);
  EXPECT_NEAR(diagonal.hesse().r, std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(diagonal.length(), std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(diagonal.SignedDistance({0, 0}), -std::sqrt(0.5), 1e-12);
}

TEST(LineSegmentTest, AngleDifferencesWrapForUndirectedLines) {
  EXPECT_NEAR(LineAngleDiff(0.01, M_PI - 0.01), -0.02, 1e-12);
  EXPECT_NEAR(LineAngleDiff(M_PI - 0.01, 0.01), 0.02, 1e-12);
  EXPECT_NEAR(LineDirectionAngle({-1, 0}), 0.0, 1e-12);
  const LineSegment s{{1, 0}, {2, 0}, true};
  const LineSegment moved = s.Transformed(core::Pose2(0, 0, M_PI));
  EXPECT_NEAR(moved.a.x(), -1.0, 1e-12);
  EXPECT_TRUE(moved.oriented);
  EXPECT_TRUE(moved.FacesAwayFrom(s));
  EXPECT_FALSE(LineSegment({{1, 0}, {2, 0}}).FacesAwayFrom(moved));  // unoriented
}

TEST(HoughLinesTest, FindsASegmentAndRefusesAMismatchedPicture) {
  BinaryImage image{40, 20, std::vector<uint8_t>(800, 0)};
  for (int x = 5; x < 35; ++x) image.pixels[10 * 40 + x] = 1;
  auto segments = DetectHoughSegments(image, {});
  ASSERT_TRUE(segments.ok()) << segments.status().ToString();
  ASSERT_FALSE(segments->empty());
  EXPECT_NEAR((*segments)[0].a.y(), 10.5, 1e-9);
  EXPECT_GT((*segments)[0].length(), 25.0);
  image.pixels.pop_back();
  EXPECT_EQ(DetectHoughSegments(image, {}).status().code(), core::StatusCode::kInvalidArgument);
  HoughOptions bad;
  bad.min_votes = 0;
  EXPECT_NE(DetectHoughSegments(image, bad).status().message().find("min_votes"),
            std::string::npos);
}

TEST(LineConsolidationTest, OneThickEdgeBecomesOneRefittedSegment) {
  // An edge three pixels thick (rows 9..11) between x = 4 and x = 56.
  BinaryImage image{60, 20, std::vector<uint8_t>(1200, 0)};
  for (int y = 9; y <= 11; ++y)
    for (int x = 4; x <= 56; ++x) image.pixels[y * 60 + x] = 1;
  auto raw = DetectHoughSegments(image, {});
  ASSERT_TRUE(raw.ok());
  EXPECT_GT(raw->size(), 1u);  // the many segments one thick edge yields
  const auto lines = ConsolidateSegments(*raw, image, {});
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NEAR(lines[0].a.y(), 10.5, 0.05);  // the refit finds the edge's centre line
  EXPECT_NEAR(lines[0].b.y(), 10.5, 0.05);
  EXPECT_NEAR(lines[0].length(), 52.0, 1.0);
}

TEST(LineFeaturesTest, StaticHallGivesOneOrientedLinePerFace) {
  const core::OccupancyGrid hall = testing::HallMap();
  auto features = ExtractLineFeatures(hall, StaticLineOptions());
  ASSERT_TRUE(features.ok());
  int south_wall = 0, stub_faces = 0;
  for (const LineSegment& l : features->lines) {
    EXPECT_TRUE(l.oriented);
    if (l.length() > 15 && std::abs(l.midpoint().y() - 0.125) < 0.02) ++south_wall;
    if (l.length() > 5 && std::abs(l.midpoint().x() - 12.0) < 0.1) ++stub_faces;
  }
  EXPECT_EQ(south_wall, 1);  // the wall is 3 cells thick, its face one line
  EXPECT_EQ(stub_faces, 2);  // a thin wall's two faces stay two lines
}

// Strong cells two cells thick along y = 1 m from x = 1 m, `length_m` long, in an unknown 3 m
// square at `resolution_m`: a temporary map's view of one face.
core::OccupancyGrid FaceAt(double resolution_m, double length_m) {
  const int n = static_cast<int>(std::lround(3.0 / resolution_m));
  core::OccupancyGrid grid{core::GridGeometry(resolution_m, n, n)};
  const core::GridGeometry& g = grid.geometry();
  for (double x = 1.0 + resolution_m / 2; x < 1.0 + length_m; x += resolution_m) {
    grid.SetLogOdds(g.WorldToCell({x, 1.0 + resolution_m / 2}), 4.0f);
    grid.SetLogOdds(g.WorldToCell({x, 1.0 - resolution_m / 2}), 4.0f);
  }
  return grid;
}

// Lengths are the building's: a face of 0.8 m is one line and one of 0.4 m is none, at 2.5, 5
// and 10 cm alike (in cells, 10 of them, the 0.4 m face was a line at 2.5 cm and the 0.8 m
// face none at 10 cm; at 5 cm a Hough segment across the two rows of cells made it two).
TEST(LineFeaturesTest, TheSameFaceGivesTheSameLinesAtAnyResolution) {
  for (const double r : {0.025, 0.05, 0.10}) {
    auto long_face = ExtractLineFeatures(FaceAt(r, 0.8), LineFeatureOptions());
    ASSERT_TRUE(long_face.ok()) << long_face.status().ToString();
    ASSERT_EQ(long_face->lines.size(), 1u) << r;
    EXPECT_NEAR(long_face->lines[0].length(), 0.8, 2 * r) << r;
    EXPECT_NEAR(long_face->lines[0].midpoint().y(), 1.0, r) << r;
    auto short_face = ExtractLineFeatures(FaceAt(r, 0.4), LineFeatureOptions());
    ASSERT_TRUE(short_face.ok());
    EXPECT_TRUE(short_face->lines.empty()) << r;
  }
}

// At 0.05 m the lengths are the picture options the method was measured with.
TEST(LineFeaturesTest, PictureOptionsAtFiveCentimetres) {
  const HoughOptions h = HoughOptionsFor(LineFeatureOptions(), 0.05);
  EXPECT_EQ(h.min_votes, 12);
  EXPECT_DOUBLE_EQ(h.min_length_cells, 10.0);
  EXPECT_DOUBLE_EQ(h.max_gap_cells, 4.0);
  EXPECT_DOUBLE_EQ(h.rho_cells, 1.0);
  const ConsolidationOptions c = ConsolidationOptionsFor(StaticLineOptions(), 0.05);
  EXPECT_DOUBLE_EQ(c.max_gap_cells, 6.0);
  EXPECT_DOUBLE_EQ(c.min_length_cells, 10.0);
  EXPECT_DOUBLE_EQ(c.max_normal_distance_cells, 1.0);
  EXPECT_DOUBLE_EQ(c.fit_band_cells, 0.8);
  EXPECT_EQ(HoughOptionsFor(LineFeatureOptions(), 0.5).min_votes, 3);  // the floors
  EXPECT_DOUBLE_EQ(ConsolidationOptionsFor(LineFeatureOptions(), 0.5).min_length_cells, 2.0);
}

TEST(DominantDirectionsTest, AxisAlignedAndTurnedHalls) {
  auto axis = StaticMapFeatures::Compute(testing::HallMap());
  ASSERT_TRUE(axis.ok());
  const double p = axis->directions().primary_rad, s = axis->directions().secondary_rad;
  EXPECT_NEAR(std::min(std::abs(std::sin(p)), std::abs(std::cos(p))), 0.0, 0.01);
  EXPECT_NEAR(std::abs(std::cos(p - s)), 0.0, 0.02);  // perpendicular
  const DominantDirections none = FindDominantDirections({});
  EXPECT_EQ(none.primary_rad, 0.0);
  EXPECT_NEAR(none.secondary_rad, M_PI / 2, 1e-12);
}

TEST(StaticFeaturesTest, SurfaceFieldPeaksAtTheWallFace) {
  auto f = StaticMapFeatures::Compute(testing::HallMap());
  ASSERT_TRUE(f.ok());
  // South wall: rows 0..2 occupied, surface row centre y = 0.125, face y = 0.15.
  EXPECT_NEAR(f->SurfaceField({10.01, 0.125}), 1.0, 1e-6);  // flat along the wall ...
  EXPECT_NEAR(f->SurfaceField({10.0, 0.15}), 1.0, 1e-6);    // ... out to its face
  EXPECT_NEAR(f->SurfaceField({10.0, 0.1375}), 1.0, 1e-6);
  EXPECT_LT(f->SurfaceField({10.0, 0.35}), 0.2);
  EXPECT_TRUE(f->OnOccupied({10.0, 0.05}));
  EXPECT_FALSE(f->OnOccupied({10.0, 1.0}));
  EXPECT_EQ(f->SurfaceField({-5.0, 3.0}), 0.0);  // outside the map
}

}  // namespace
}  // namespace fleetmap::aggregator
