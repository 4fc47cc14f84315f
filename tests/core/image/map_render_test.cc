#include "core/image/map_render.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/io/file_io.h"
#include "core/map/pgm.h"
#include "tests/support/scratch_folder.h"

namespace fleetmap::core {
namespace {

using ::testing::HasSubstr;

const Bgr kWhite{255, 255, 255};
const Bgr kBlack{0, 0, 0};
const Bgr kGrey{205, 205, 205};

class MapRenderTest : public ::testing::Test {
 protected:
  std::string File(const std::string& name) const { return folder_.File(name); }

  fleetmap::testing::ScratchFolder folder_;
};

// 4 x 3 cells: row 0 (bottom) free except an occupied cell at x = 1, row 2 (top) occupied at
// x = 3, everything else unknown.
OccupancyGrid SmallGrid() {
  OccupancyGrid grid(GridGeometry(0.1, 4, 3, Pose2(-1.0, 2.0, 0.5)));
  for (int x = 0; x < 4; ++x) grid.SetState({x, 0}, CellState::kFree);
  grid.SetState({1, 0}, CellState::kOccupied);
  grid.SetState({3, 2}, CellState::kOccupied);
  return grid;
}

TEST_F(MapRenderTest, GridBottomRowIsImageBottomRow) {
  const Result<BgrImage> image = RenderGrid(SmallGrid());
  ASSERT_TRUE(image.ok()) << image.status().ToString();
  ASSERT_EQ(image->width, 4);
  ASSERT_EQ(image->height, 3);
  EXPECT_EQ(image->at(0, 2), kWhite);  // grid (0, 0): bottom image row
  EXPECT_EQ(image->at(1, 2), kBlack);  // grid (1, 0)
  EXPECT_EQ(image->at(3, 0), kBlack);  // grid (3, 2): top image row
  EXPECT_EQ(image->at(0, 0), kGrey);
  EXPECT_EQ(image->at(2, 1), kGrey);
}

TEST_F(MapRenderTest, PngIsWrittenAndReadsBack) {
  ASSERT_TRUE(RenderGridToPng(SmallGrid(), File("map.png")).ok());
  const Result<std::string> bytes = ReadFileBytes(File("map.png"), 1 << 20);
  ASSERT_TRUE(bytes.ok());
  EXPECT_EQ(bytes->substr(1, 3), "PNG");
  const Result<BgrImage> image = ReadBgrImage(File("map.png"));  // cv::imread
  ASSERT_TRUE(image.ok()) << image.status().ToString();
  ASSERT_EQ(image->width, 4);
  ASSERT_EQ(image->height, 3);
  EXPECT_EQ(image->at(0, 2), kWhite);
  EXPECT_EQ(image->at(1, 2), kBlack);
  EXPECT_EQ(image->at(3, 0), kBlack);
  EXPECT_EQ(image->at(2, 0), kGrey);
}

TEST_F(MapRenderTest, ScaleEnlargesEveryCellIntoABlock) {
  RenderOptions options;
  options.scale_pixels_per_cell = 3;
  options.occupied_color = Bgr{0, 0, 255};  // red, to check the channel order
  ASSERT_TRUE(RenderGridToPng(SmallGrid(), File("big.png"), options).ok());
  const Result<BgrImage> image = ReadBgrImage(File("big.png"));
  ASSERT_TRUE(image.ok()) << image.status().ToString();
  ASSERT_EQ(image->width, 12);
  ASSERT_EQ(image->height, 9);
  for (int row = 6; row < 9; ++row) {  // grid (1, 0): columns 3..5 of the bottom block row
    EXPECT_EQ(image->at(2, row), kWhite);
    for (int col = 3; col < 6; ++col) EXPECT_EQ(image->at(col, row), (Bgr{0, 0, 255}));
    EXPECT_EQ(image->at(6, row), kWhite);
  }
  EXPECT_EQ(image->at(9, 0), (Bgr{0, 0, 255}));  // grid (3, 2)
  EXPECT_EQ(image->at(11, 2), (Bgr{0, 0, 255}));
  EXPECT_EQ(image->at(8, 2), kGrey);
}

TEST_F(MapRenderTest, ThresholdsDecideTheColour) {
  OccupancyGrid grid(GridGeometry(0.1, 2, 1));
  grid.SetLogOdds({0, 0}, ProbabilityToLogOdds(0.6));
  grid.SetLogOdds({1, 0}, ProbabilityToLogOdds(0.3));
  const Result<BgrImage> plain = RenderGrid(grid);
  ASSERT_TRUE(plain.ok());
  EXPECT_EQ(plain->at(0, 0), kGrey);
  EXPECT_EQ(plain->at(1, 0), kGrey);
  RenderOptions options;
  options.thresholds.occupied_probability = 0.55;
  options.thresholds.free_probability = 0.35;
  const Result<BgrImage> strict = RenderGrid(grid, options);
  ASSERT_TRUE(strict.ok());
  EXPECT_EQ(strict->at(0, 0), kBlack);
  EXPECT_EQ(strict->at(1, 0), kWhite);
}

TEST_F(MapRenderTest, BadOptionsAndPathsAreStatuses) {
  RenderOptions options;
  options.scale_pixels_per_cell = 0;
  const Result<BgrImage> zero = RenderGrid(SmallGrid(), options);
  ASSERT_FALSE(zero.ok());
  EXPECT_THAT(zero.status().message(), HasSubstr("scale_pixels_per_cell must be 1..64, got 0"));

  options.scale_pixels_per_cell = 64;
  const OccupancyGrid big(GridGeometry(0.1, 1000, 1000));
  const Result<BgrImage> huge = RenderGrid(big, options);
  ASSERT_FALSE(huge.ok());
  EXPECT_EQ(huge.status().code(), StatusCode::kOutOfRange);

  const Status no_folder = RenderGridToPng(SmallGrid(), File("missing/map.png"));
  EXPECT_EQ(no_folder.code(), StatusCode::kIoError);
  EXPECT_THAT(no_folder.message(), HasSubstr("missing/map.png"));

  const Result<BgrImage> absent = ReadBgrImage(File("absent.png"));
  ASSERT_FALSE(absent.ok());
  EXPECT_THAT(absent.status().message(), HasSubstr("absent.png"));
}

}  // namespace
}  // namespace fleetmap::core
