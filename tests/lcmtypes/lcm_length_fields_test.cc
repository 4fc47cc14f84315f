// What LCM 1.3.1's generated code does with bad lengths, so that the processes' LCM edge
// guards against it: it trusts num_* and never compares it with the vector, and a corrupt
// array or string length made lcm-gen's decode() throw (cmake/LcmDecodeBounds.cmake makes it
// return < 0 instead).

#include <gtest/gtest.h>

#include <vector>

#include "tests/lcmtypes/lcm_samples.h"

namespace fleetmap {
namespace {

using lcmtypes::testing::Bytes;
using lcmtypes::testing::Decode;
using lcmtypes::testing::Encode;
using lcmtypes::testing::MakeSample;

TEST(LcmTypesTest, LengthFieldShorterThanVectorSilentlyDropsTheRest) {
  laser_scan_t scan = MakeSample<laser_scan_t>();
  scan.num_ranges = 2;               // ranges_m holds 5
  const Bytes bytes = Encode(scan);  // Encode() also checks encode() returned the full size.
  int status = 0;
  const laser_scan_t received = Decode<laser_scan_t>(bytes, &status);
  ASSERT_EQ(status, static_cast<int>(bytes.size()));
  EXPECT_EQ(received.ranges_m, std::vector<float>({1.5f, 2.25f}));
}

TEST(LcmTypesTest, EncodedSizeFollowsLengthFieldNotVector) {
  // So with num_ranges > ranges_m.size() encode() succeeds and reads past the vector's end
  // (AddressSanitizer: heap-buffer-overflow). That case is undefined behaviour and is not run
  // here: the LCM edge must set every num_* from size() right before encoding.
  laser_scan_t scan = MakeSample<laser_scan_t>();
  const int size = scan.getEncodedSize();
  scan.num_ranges += 3;
  EXPECT_EQ(scan.getEncodedSize(), size + 3 * static_cast<int>(sizeof(float)));
}

TEST(LcmTypesTest, NegativeLengthFieldFailsEncodeIntoExactBuffer) {
  laser_scan_t scan = MakeSample<laser_scan_t>();
  scan.num_ranges = -1;  // getEncodedSize() then undercounts, so the exact buffer is too small.
  Bytes bytes(scan.getEncodedSize());
  EXPECT_LT(scan.encode(bytes.data(), 0, static_cast<int>(bytes.size())), 0);
}

TEST(LcmTypesTest, DecodeRefusesNegativeArrayLength) {
  // With room to spare, encode() writes num_ranges = -1. lcm-gen's decode() called
  // vector::resize(-1) and threw; cmake/LcmDecodeBounds.cmake makes it return < 0.
  laser_scan_t scan = MakeSample<laser_scan_t>();
  scan.num_ranges = -1;
  Bytes bytes(1024);
  const int size = scan.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  ASSERT_GT(size, 0);
  bytes.resize(size);
  laser_scan_t received;
  EXPECT_LT(received.decode(bytes.data(), 0, size), 0);
}

TEST(LcmTypesTest, DecodeRefusesZeroStringLength) {
  // A string is sent as int32 length (with the '\0') + bytes; length 0 made lcm-gen's decode()
  // call string::assign(p, -1), which threw; cmake/LcmDecodeBounds.cmake makes it return < 0.
  // Byte 16 is the length of vehicle_id (after hash and utime).
  Bytes bytes = Encode(MakeSample<laser_scan_t>());
  ASSERT_EQ(bytes[19], MakeSample<laser_scan_t>().vehicle_id.size() + 1);
  bytes[16] = bytes[17] = bytes[18] = bytes[19] = 0;
  laser_scan_t received;
  EXPECT_LT(received.decode(bytes.data(), 0, static_cast<int>(bytes.size())), 0);
}

}  // namespace
}  // namespace fleetmap
