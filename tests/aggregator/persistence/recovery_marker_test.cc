#include "aggregator/persistence/recovery_marker.h"

#include <gtest/gtest.h>

#include "tests/aggregator/test_files.h"

namespace fleetmap::aggregator {
namespace {

TEST(RecoveryMarkerTest, WrittenThenReadBackAndGarbageIsNamed) {
  fleetmap::testing::ScratchFolder folder;
  auto none = ReadRecoveryMarker(folder.path());
  ASSERT_TRUE(none.ok());
  EXPECT_FALSE(none->has_value());

  ASSERT_TRUE(WriteRecoveryMarker(folder.path(), {1796517452123456, 52, 1796517452.123}).ok());
  auto marker = ReadRecoveryMarker(folder.path());
  ASSERT_TRUE(marker.ok()) << marker.status().ToString();
  ASSERT_TRUE(marker->has_value());
  EXPECT_EQ((*marker)->id, 1796517452123456);
  EXPECT_EQ((*marker)->version, 52u);
  EXPECT_NEAR((*marker)->at_s, 1796517452.123, 1e-3);

  testing::WriteAll(folder.File(kRecoveryMarkerName), {'v', 'e', 'r', 's', 'i', 'o', 'n'});
  auto garbage = ReadRecoveryMarker(folder.path());
  ASSERT_FALSE(garbage.ok());
  EXPECT_EQ(garbage.status().code(), core::StatusCode::kDataLoss);
  EXPECT_NE(garbage.status().message().find(kRecoveryMarkerName), std::string::npos);
}

}  // namespace
}  // namespace fleetmap::aggregator
