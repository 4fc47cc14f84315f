// Inputs on which the fuzz targets (fuzz/, docs/fuzzing.md) found the LCM decoders crashing or
// misbehaving; tests/data/fuzz/<target>/ holds the fuzzers' own inputs. Fixed in
// cmake/LcmDecodeBounds.cmake (the generated decoders) and lcmtypes/convert.cc.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <string>
#include <vector>

#include "core/io/file_io.h"
#include "fleetmap/merge_report_t.hpp"
#include "fleetmap/status_t.hpp"
#include "lcmtypes/convert.h"
#include "lcmtypes/transport_convert.h"

// The largest single allocation while `g_watch` is set: what a hostile length field makes the
// decoder allocate. Counted by replacing the global operator new of this test binary.
namespace {
std::atomic<bool> g_watch{false};
std::atomic<size_t> g_largest{0};
}  // namespace

// Not inlined: GCC would otherwise see free() meet a pointer from operator new at call sites
// and warn (-Wmismatched-new-delete), although both sides are these replacements.
__attribute__((noinline)) void* operator new(std::size_t n) {
  if (g_watch && n > g_largest) g_largest = n;
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
__attribute__((noinline)) void operator delete(void* p) noexcept { std::free(p); }
__attribute__((noinline)) void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace fleetmap::lcmtypes {
namespace {

std::string Fixture(const std::string& name) {
  auto bytes = core::ReadFileBytes(FLEETMAP_SOURCE_DIR "/tests/data/fuzz/" + name, 1 << 20);
  EXPECT_TRUE(bytes.ok()) << bytes.status().ToString();
  return bytes.ok() ? *bytes : std::string();
}

template <typename T>
std::vector<uint8_t> Encode(const T& msg) {
  std::vector<uint8_t> buf(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(buf.data(), 0, static_cast<int>(buf.size()));
  return buf;
}

// LCM writes integers big-endian.
void PutBe32(std::vector<uint8_t>& bytes, size_t at, uint32_t v) {
  for (int i = 0; i < 4; ++i) bytes[at + i] = static_cast<uint8_t>(v >> (24 - 8 * i));
}

// Decodes and returns the largest allocation the decoding made.
template <typename T>
size_t LargestAllocation(const std::vector<uint8_t>& bytes, bool* ok) {
  g_largest = 0;
  g_watch = true;
  *ok = Decode<T>(bytes.data(), static_cast<int>(bytes.size())).ok();
  g_watch = false;
  return g_largest;
}

// lcm-gen's decoders computed `length - 1` of a string length field before checking it was
// positive: INT32_MIN overflowed (UBSan), 0 asked std::string for SIZE_MAX bytes.
TEST(LcmFuzzRegressionTest, StringLengthsBelowOneAreMalformed) {
  for (const char* name : {"lcm_odometry/string_length_int32_min"}) {
    const std::string bytes = Fixture(name);
    EXPECT_FALSE(Decode<fleetmap::odometry_t>(bytes.data(), int(bytes.size())).ok()) << name;
  }
  const std::string pose = Fixture("lcm_pose/string_length_int32_min");
  EXPECT_FALSE(Decode<fleetmap::pose_with_covariance_t>(pose.data(), int(pose.size())).ok());
  fleetmap::odometry_t odom{};
  odom.vehicle_id = "v1";
  std::vector<uint8_t> bytes = Encode(odom);
  ASSERT_TRUE(Decode<fleetmap::odometry_t>(bytes.data(), int(bytes.size())).ok());
  for (const uint32_t length : {0x80000000u, 0u, 0xFFFFFFFFu}) {
    PutBe32(bytes, 16, length);  // after the fingerprint and utime
    EXPECT_FALSE(Decode<fleetmap::odometry_t>(bytes.data(), int(bytes.size())).ok()) << length;
  }
}

// lcm-gen's decoders resized an array to its count before checking that the message holds
// that many elements: a 30-byte payload claiming 2^31 floats allocated (and zeroed) 8 GB.
TEST(LcmFuzzRegressionTest, ArrayCountsBeyondTheMessageAllocateNothing) {
  const std::string report = Fixture("lcm_messages/merge_report_huge_match_count");
  bool ok = true;
  EXPECT_LT(LargestAllocation<fleetmap::merge_report_t>(
                std::vector<uint8_t>(report.begin(), report.end()), &ok),
            size_t{1} << 16);
  EXPECT_FALSE(ok);

  fleetmap::laser_scan_t scan{};
  scan.vehicle_id = "v1";
  std::vector<uint8_t> bytes = Encode(scan);
  PutBe32(bytes, bytes.size() - 8, 0x7FFFFFFF);  // num_ranges, followed by num_intensities only
  EXPECT_LT(LargestAllocation<fleetmap::laser_scan_t>(bytes, &ok), size_t{1} << 16);
  EXPECT_FALSE(ok);

  fleetmap::status_t status{};
  bytes = Encode(status);
  PutBe32(bytes, bytes.size() - 4, 0x7FFFFFFF);  // num_counters, the last field
  EXPECT_LT(LargestAllocation<fleetmap::status_t>(bytes, &ok), size_t{1} << 16);
  EXPECT_FALSE(ok);

  fleetmap::tempmap_tile_t tile{};
  tile.vehicle_id = "v1";
  bytes = Encode(tile);
  PutBe32(bytes, bytes.size() - 8, 0x7FFFFFFF);  // tile.payload_size, then tile.crc32
  EXPECT_LT(LargestAllocation<fleetmap::tempmap_tile_t>(bytes, &ok), size_t{1} << 16);
  EXPECT_FALSE(ok);
  for (const uint32_t count : {0x80000000u, 0xFFFFFFFFu}) {  // negative counts
    PutBe32(bytes, bytes.size() - 8, count);
    EXPECT_FALSE(Decode<fleetmap::tempmap_tile_t>(bytes.data(), int(bytes.size())).ok());
  }
}

// A vehicle id with a NUL passed validation but could not be sent back: LCM encodes a string
// only up to its first NUL, so the id in an acknowledgement (or a re-published scan) differed
// and the message was longer than its encoding.
TEST(LcmFuzzRegressionTest, VehicleIdsAreMadeOfPrintableCharacters) {
  const std::string bytes = Fixture("lcm_laser_scan/vehicle_id_with_nul");
  auto msg = Decode<fleetmap::laser_scan_t>(bytes.data(), int(bytes.size()));
  ASSERT_TRUE(msg.ok());
  EXPECT_EQ(msg->vehicle_id.find('\0'), 8u);
  EXPECT_FALSE(FromMessage(*msg).ok());
  EXPECT_TRUE(CheckVehicleId("agv_1").ok());
  for (const std::string& id : {std::string("agv\0"
                                            "1",
                                            5),
                                std::string("agv 1"), std::string("agv\n"), std::string("\x80")}) {
    EXPECT_FALSE(CheckVehicleId(id).ok()) << id;
  }
  fleetmap::tempmap_tile_t tile{};
  tile.vehicle_id = std::string("a\0b", 3);
  EXPECT_NE(FromMessage(tile).status().message().find("printable"), std::string::npos);
}

// Seen while fixing the above: FromMessage(map_delta_t) computed base_version + 1, which
// overflows at INT32_MAX.
TEST(LcmFuzzRegressionTest, DeltaAtTheLastVersionIsRefused) {
  fleetmap::map_delta_t delta{};
  delta.base_version = INT32_MAX;
  delta.new_version = INT32_MIN;
  EXPECT_FALSE(FromMessage(delta).ok());
}

}  // namespace
}  // namespace fleetmap::lcmtypes
