#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "eval/carmen/relations.h"

namespace fleetmap::eval::carmen {
namespace {

std::string WriteFile(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

TEST(TrajectoryTest, ReadsSortsAndScoresAnotherSystemsTrajectory) {
  // Out of order and with a comment, as another program may write it.
  const std::string path =
      WriteFile("trajectory.txt", "# t x y theta\n2.0 1.0 0.5 0.1\n1.0 0.0 0.0 0.0\n");
  auto trajectory = ReadTrajectory(path);
  ASSERT_TRUE(trajectory.ok()) << trajectory.status().ToString();
  ASSERT_EQ(trajectory->size(), 2u);
  EXPECT_DOUBLE_EQ((*trajectory)[0].stamp_s, 1.0);
  EXPECT_DOUBLE_EQ((*trajectory)[1].pose.theta_rad, 0.1);
  const std::vector<Relation> relations = {{1.0, 2.0, core::Pose2(1.0, 0.5, 0.1)}};
  const RelationErrors e = ScoreRelations(relations, *trajectory);
  EXPECT_EQ(e.used, 1);
  EXPECT_NEAR(e.trans_mean_m, 0.0, 1e-12);
}

TEST(TrajectoryTest, MalformedLinesAndMissingFilesAreErrors) {
  auto bad = ReadTrajectory(WriteFile("bad_trajectory.txt", "1.0 0.0 0.0 0.0\n2.0 nan 0 0\n"));
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().ToString().find("line 2"), std::string::npos);
  EXPECT_FALSE(ReadTrajectory(::testing::TempDir() + "no_such_trajectory.txt").ok());
}

TEST(TrajectoryTest, AWrittenTrajectoryReadsBackAndAnUnwritablePathIsAnError) {
  const std::vector<TimedPose> written = {{1068.123456, core::Pose2(1.5, -2.25, 3.1)},
                                          {1068.323456, core::Pose2(1.6, -2.2, -3.1)}};
  const std::string path = ::testing::TempDir() + "written_trajectory.txt";
  ASSERT_TRUE(WriteTrajectory(path, written).ok());
  auto read = ReadTrajectory(path);
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  ASSERT_EQ(read->size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR((*read)[i].stamp_s, written[i].stamp_s, 1e-6);
    EXPECT_NEAR((*read)[i].pose.x_m, written[i].pose.x_m, 1e-6);
    EXPECT_NEAR((*read)[i].pose.y_m, written[i].pose.y_m, 1e-6);
    EXPECT_NEAR((*read)[i].pose.theta_rad, written[i].pose.theta_rad, 1e-6);
  }
  const core::Status s = WriteTrajectory(::testing::TempDir() + "no_such_folder/t.txt", written);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.ToString().find("no_such_folder"), std::string::npos);
  // A write that fails only after the text was written (here: the name is a folder's): an
  // error, and nothing left behind. The full disk is the same path (core::WriteFileAtomically).
  const std::string folder = ::testing::TempDir() + "trajectory_folder";
  std::filesystem::create_directories(folder);
  EXPECT_FALSE(WriteTrajectory(folder, written).ok());
  EXPECT_TRUE(std::filesystem::is_directory(folder));
}

}  // namespace
}  // namespace fleetmap::eval::carmen
