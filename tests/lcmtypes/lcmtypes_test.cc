// Tests of the generated LCM types (package fleetmap): every type's encoding round trip,
// and decode() refusing truncated bytes and another type's message.

#include <gtest/gtest.h>

#include "tests/lcmtypes/lcm_expect_same.h"
#include "tests/lcmtypes/lcm_samples.h"

namespace fleetmap {
namespace {

using lcmtypes::testing::Bytes;
using lcmtypes::testing::Decode;
using lcmtypes::testing::Encode;
using lcmtypes::testing::ExpectSame;
using lcmtypes::testing::MakeSample;

// The same checks for every type.
template <typename T>
class LcmTypeTest : public ::testing::Test {};

using AllTypes =
    ::testing::Types<pose2d_t, laser_scan_t, odometry_t, pose_with_covariance_t, divergence_t,
                     map_tile_t, tempmap_tile_t, tempmap_ack_t, map_delta_t, map_keyframe_t,
                     map_request_t, line_match_t, merge_report_t, status_t>;
TYPED_TEST_SUITE(LcmTypeTest, AllTypes);

TYPED_TEST(LcmTypeTest, SampleDiffersFromDefault) {
  // Guards the round trip below against samples that a zero-filled decode would also match.
  EXPECT_NE(Encode(MakeSample<TypeParam>()), Encode(TypeParam()));
}

TYPED_TEST(LcmTypeTest, EncodeDecodeRoundTrip) {
  const TypeParam sent = MakeSample<TypeParam>();
  const Bytes bytes = Encode(sent);
  int status = 0;
  const TypeParam received = Decode<TypeParam>(bytes, &status);
  ASSERT_EQ(status, static_cast<int>(bytes.size()));
  ExpectSame(sent, received);
  EXPECT_EQ(Encode(received), bytes);  // Also covers any field ExpectSame might miss.
}

TYPED_TEST(LcmTypeTest, EveryTruncationIsRejected) {
  const Bytes bytes = Encode(MakeSample<TypeParam>());
  for (int size = 0; size < static_cast<int>(bytes.size()); ++size) {
    int status = 0;
    Decode<TypeParam>(bytes, &status, size);
    EXPECT_LT(status, 0) << "decoding the first " << size << " of " << bytes.size() << " bytes";
  }
}

TYPED_TEST(LcmTypeTest, EncodeIntoTooSmallBufferFails) {
  const TypeParam msg = MakeSample<TypeParam>();
  Bytes bytes(msg.getEncodedSize());
  EXPECT_LT(msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()) - 1), 0);
}

TEST(LcmTypesTest, OtherTypeIsRejectedByHash) {
  const Bytes bytes = Encode(MakeSample<map_delta_t>());
  int status = 0;
  Decode<map_keyframe_t>(bytes, &status);
  EXPECT_LT(status, 0);
}

}  // namespace
}  // namespace fleetmap
