#include "core/result.h"

#include <gtest/gtest.h>

namespace fleetmap::core {
namespace {

Result<int> ParsePositive(int v) {
  if (v <= 0) return InvalidArgument("value must be positive");
  return v;
}

Status Chain(int v) {
  FLEETMAP_RETURN_IF_ERROR(ParsePositive(v).status());
  return OkStatus();
}

TEST(ResultTest, HoldsValueOrError) {
  auto good = ParsePositive(3);
  ASSERT_TRUE(good.ok());
  EXPECT_EQ(*good, 3);
  EXPECT_TRUE(good.status().ok());
  auto bad = ParsePositive(-1);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(bad.status().ToString(), "INVALID_ARGUMENT: value must be positive");
}

TEST(ResultTest, ContextAndEarlyReturn) {
  EXPECT_TRUE(Chain(1).ok());
  const Status s = Chain(0).WithContext("map.yaml");
  EXPECT_EQ(s.message(), "map.yaml: value must be positive");
}

}  // namespace
}  // namespace fleetmap::core
