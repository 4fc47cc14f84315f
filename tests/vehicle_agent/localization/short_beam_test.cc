#include "vehicle_agent/localization/short_beam.h"

#include <gtest/gtest.h>

#include "tests/vehicle_agent/test_grids.h"

namespace fleetmap::vehicle_agent {
namespace {

class ShortBeamTest : public ::testing::Test {
 protected:
  ShortBeamTest() : map_(test_grids::Room(2)), field_({}) {
    test_grids::AddBox(map_, 5.0, 0.0, 5.2, 4.0);  // an inner wall from the bottom to y = 4
    // Unknown space beyond x = 8.
    for (int y = 2; y < 118; ++y)
      for (int x = 160; x < 198; ++x) map_.SetState({x, y}, core::CellState::kUnknown);
    field_.SetMap(map_);
  }
  bool Short(double x0, double y0, double x1, double y1) const {
    return EndsShortInFreeSpace(map_, field_, {x0, y0}, {x1, y1}, 0.3);
  }
  core::OccupancyGrid map_;
  LikelihoodField field_;
};

TEST_F(ShortBeamTest, ABeamEndingInOpenFreeSpaceIsShort) {
  EXPECT_TRUE(Short(1.0, 2.0, 4.0, 2.0));
  EXPECT_TRUE(Short(1.0, 1.0, 6.0, 5.5));  // passes above the inner wall's end
}

TEST_F(ShortBeamTest, ABeamThroughAMappedWallIsNot) {
  EXPECT_FALSE(Short(1.0, 2.0, 7.0, 2.0));
  EXPECT_FALSE(Short(7.0, 3.9, 1.0, 3.9));  // grazes the wall's last row
}

TEST_F(ShortBeamTest, AWallWithinTheMarginBeforeTheEndDoesNotCount) {
  // The end lies 0.2 m past the wall's face: a pose a little off, not a beam through a wall.
  EXPECT_TRUE(Short(1.0, 2.0, 4.9, 2.0));
}

TEST_F(ShortBeamTest, AnEndInUnknownOrOffTheMapIsNot) {
  EXPECT_FALSE(Short(6.0, 5.0, 9.0, 5.0));
  EXPECT_FALSE(Short(6.0, 5.0, 12.0, 5.0));
}

}  // namespace
}  // namespace fleetmap::vehicle_agent
