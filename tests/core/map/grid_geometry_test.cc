#include "core/map/grid_geometry.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fleetmap::core {
namespace {

TEST(GridGeometryTest, WorldToCellAndBackWithoutYaw) {
  const GridGeometry g(0.05, 100, 50, Pose2(-1.0, 2.0, 0.0));
  EXPECT_EQ(g.WorldToCell({-1.0 + 0.026, 2.0 + 0.074}), (CellIndex{0, 1}));
  const Eigen::Vector2d c = g.CellCenter({10, 20});
  EXPECT_NEAR(c.x(), -1.0 + 10.5 * 0.05, 1e-12);
  EXPECT_NEAR(c.y(), 2.0 + 20.5 * 0.05, 1e-12);
  EXPECT_EQ(g.WorldToCell(c), (CellIndex{10, 20}));
}

TEST(GridGeometryTest, OriginYawRotatesTheGrid) {
  // Grid x axis points along world +y.
  const GridGeometry g(0.1, 10, 10, Pose2(5.0, 0.0, M_PI / 2));
  const Eigen::Vector2d c = g.CellCenter({3, 0});
  EXPECT_NEAR(c.x(), 5.0 - 0.05, 1e-9);
  EXPECT_NEAR(c.y(), 0.35, 1e-9);
  EXPECT_EQ(g.WorldToCell(c), (CellIndex{3, 0}));
}

TEST(GridGeometryTest, ValidateRejectsBadGeometry) {
  EXPECT_TRUE(GridGeometry(0.05, 10, 10).Validate().ok());
  EXPECT_EQ(GridGeometry(0.0, 10, 10).Validate().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(GridGeometry(NAN, 10, 10).Validate().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(GridGeometry(0.05, 0, 10).Validate().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(GridGeometry(0.05, 20000, 20000).Validate().code(), StatusCode::kOutOfRange);
  EXPECT_EQ(GridGeometry(0.05, 10, 10, Pose2(0, INFINITY, 0)).Validate().code(),
            StatusCode::kInvalidArgument);
}

TEST(GridGeometryTest, ContainsWindows) {
  const GridGeometry g(0.05, 100, 50);
  EXPECT_TRUE(g.Contains(CellWindow{0, 0, 100, 50}));
  EXPECT_TRUE(g.Contains(CellWindow{64, 0, 36, 50}));
  EXPECT_FALSE(g.Contains(CellWindow{64, 0, 37, 50}));
  EXPECT_FALSE(g.Contains(CellWindow{-1, 0, 10, 10}));
  EXPECT_FALSE(g.Contains(CellIndex{100, 0}));
}

}  // namespace
}  // namespace fleetmap::core
