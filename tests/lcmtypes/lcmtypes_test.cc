// Tests of the generated LCM types (package fleetmap) and of what LCM 1.3.1's generated code
// does with bad lengths and bad bytes, so that the processes' LCM edge guards against it.

#include <gtest/gtest.h>

#include <cstdint>
#include <lcm/lcm-cpp.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "fleetmap/divergence_t.hpp"
#include "fleetmap/laser_scan_t.hpp"
#include "fleetmap/line_match_t.hpp"
#include "fleetmap/map_delta_t.hpp"
#include "fleetmap/map_keyframe_t.hpp"
#include "fleetmap/map_request_t.hpp"
#include "fleetmap/map_tile_t.hpp"
#include "fleetmap/merge_report_t.hpp"
#include "fleetmap/odometry_t.hpp"
#include "fleetmap/pose2d_t.hpp"
#include "fleetmap/pose_with_covariance_t.hpp"
#include "fleetmap/status_t.hpp"
#include "fleetmap/tempmap_ack_t.hpp"
#include "fleetmap/tempmap_tile_t.hpp"

namespace fleetmap {
namespace {

using Bytes = std::vector<uint8_t>;

template <typename T>
Bytes Encode(const T& msg) {
  Bytes bytes(msg.getEncodedSize());
  const int size = msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  EXPECT_EQ(size, static_cast<int>(bytes.size())) << T::getTypeName();
  return bytes;
}

// Decodes exactly `size` bytes (all by default); returns decode()'s result in *status.
template <typename T>
T Decode(const Bytes& bytes, int* status, int size = -1) {
  T msg;
  *status = msg.decode(bytes.data(), 0, size < 0 ? static_cast<int>(bytes.size()) : size);
  return msg;
}

// ---- Samples: every field set to a distinct non-default value, every array non-empty. ----

template <typename T>
T MakeSample();

template <>
pose2d_t MakeSample<pose2d_t>() {
  pose2d_t p;
  p.x_m = 12.5;
  p.y_m = -3.25;
  p.theta_rad = 1.0471975511965976;
  return p;
}

template <>
laser_scan_t MakeSample<laser_scan_t>() {
  laser_scan_t s;
  s.utime = 1700000000123456;
  s.vehicle_id = "agv_1";
  s.seq = 4711;
  s.angle_min_rad = -2.35619449f;
  s.angle_increment_rad = 0.00872664626f;
  s.range_min_m = 0.05f;
  s.range_max_m = 30.0f;
  s.scan_period_s = 0.04f;
  s.ranges_m = {1.5f, 2.25f, 30.5f, 0.0f, 7.125f};
  s.num_ranges = static_cast<int32_t>(s.ranges_m.size());
  s.intensities = {100.0f, 200.0f, 0.0f, 50.0f, 255.0f};
  s.num_intensities = static_cast<int32_t>(s.intensities.size());
  return s;
}

template <>
odometry_t MakeSample<odometry_t>() {
  odometry_t o;
  o.utime = 1700000000200000;
  o.vehicle_id = "agv_2";
  o.pose = MakeSample<pose2d_t>();
  o.v_mps = 0.75;
  o.omega_radps = -0.125;
  return o;
}

template <>
pose_with_covariance_t MakeSample<pose_with_covariance_t>() {
  pose_with_covariance_t p;
  p.utime = 1700000000300000;
  p.vehicle_id = "agv_3";
  p.pose = MakeSample<pose2d_t>();
  for (int i = 0; i < 9; ++i) p.covariance[i] = 0.01 * (i + 1);
  p.map_version = 17;
  return p;
}

template <>
divergence_t MakeSample<divergence_t>() {
  divergence_t d;
  d.utime = 1700000000400000;
  d.vehicle_id = "agv_4";
  d.w_avg = 0.031;
  d.w_slow = 0.042;
  d.w_fast = 0.021;
  d.d = 0.5;
  d.state = divergence_t::BUILDING;
  d.rotating = 1;
  d.tempmap_seq = 9;
  return d;
}

template <>
map_tile_t MakeSample<map_tile_t>() {
  map_tile_t t;
  t.tile_x = 3;
  t.tile_y = 4;
  t.x0_cells = 192;
  t.y0_cells = 256;
  t.width_cells = 64;
  t.height_cells = 48;
  t.tile_version = 21;
  t.codec = map_tile_t::PACKING_LOGODDS_INT8 | map_tile_t::COMPRESSION_ZSTD;
  t.payload = {0x28, 0xb5, 0x2f, 0xfd, 0x00, 0xff, 0x7f, 0x80};
  t.payload_size = static_cast<int32_t>(t.payload.size());
  t.crc32 = static_cast<int32_t>(0xdeadbeefu);
  return t;
}

template <>
tempmap_tile_t MakeSample<tempmap_tile_t>() {
  tempmap_tile_t t;
  t.utime = 1700000000500000;
  t.vehicle_id = "agv_5";
  t.tempmap_seq = 12;
  t.tile_index = 2;
  t.tile_count = 6;
  t.anchor_pose = MakeSample<pose2d_t>();
  t.grid_origin = MakeSample<pose2d_t>();
  t.grid_origin.x_m = -3.5;
  t.resolution_m = 0.05f;
  t.width_cells = 200;
  t.height_cells = 150;
  t.start_utime = 1700000000000000;
  t.end_utime = 1700000000450000;
  t.tile = MakeSample<map_tile_t>();
  return t;
}

template <>
tempmap_ack_t MakeSample<tempmap_ack_t>() {
  tempmap_ack_t a;
  a.utime = 1700000000600000;
  a.vehicle_id = "agv_6";
  a.tempmap_seq = 12;
  a.tile_count = 6;
  a.received_tiles = {0, 1, 3, 5};
  a.num_received = static_cast<int32_t>(a.received_tiles.size());
  a.outcome = tempmap_ack_t::REJECTED;
  a.reason = "too few line matches";
  a.map_version = 22;
  return a;
}

template <>
map_delta_t MakeSample<map_delta_t>() {
  map_delta_t d;
  d.utime = 1700000000700000;
  d.base_version = 22;
  d.new_version = 23;
  d.tile_index = 1;
  d.tile_count = 4;
  d.tile = MakeSample<map_tile_t>();
  return d;
}

template <>
map_keyframe_t MakeSample<map_keyframe_t>() {
  map_keyframe_t k;
  k.utime = 1700000000800000;
  k.version = 23;
  k.resolution_m = 0.05f;
  k.width_cells = 1200;
  k.height_cells = 800;
  k.origin = MakeSample<pose2d_t>();
  k.tile_size_cells = 64;
  k.tile_index = 37;
  k.tile_count = 247;
  k.tile = MakeSample<map_tile_t>();
  return k;
}

template <>
map_request_t MakeSample<map_request_t>() {
  map_request_t r;
  r.utime = 1700000000900000;
  r.vehicle_id = "agv_7";
  r.have_version = 20;
  r.tiles = {5, 6, 230};
  r.num_tiles = static_cast<int32_t>(r.tiles.size());
  return r;
}

template <>
line_match_t MakeSample<line_match_t>() {
  line_match_t m;
  m.temp_line_id = 4;
  m.static_line_id = 17;
  m.distance_diff_px = 1.5;
  m.angle_diff_deg = -0.75;
  return m;
}

template <>
merge_report_t MakeSample<merge_report_t>() {
  merge_report_t r;
  r.utime = 1700000001000000;
  r.vehicle_id = "agv_8";
  r.tempmap_seq = 13;
  r.accepted = 1;
  r.reason = "";
  r.dtheta_rad = 0.0125;
  r.dx_m = -0.04;
  r.dy_m = 0.02;
  r.score = 0.87;
  line_match_t second = MakeSample<line_match_t>();
  second.temp_line_id = 5;
  second.angle_diff_deg = 0.25;
  r.matches = {MakeSample<line_match_t>(), second};
  r.num_matches = static_cast<int32_t>(r.matches.size());
  r.cells_added = 312;
  r.cells_removed = 45;
  r.new_version = 24;
  return r;
}

template <>
status_t MakeSample<status_t>() {
  status_t s;
  s.utime = 1700000001100000;
  s.process = "aggregator";
  s.software_version = "0.1.0";
  s.map_version = 24;
  s.state = "running";
  s.authenticated = 1;
  s.counter_names = {"tempmaps_merged", "tempmaps_rejected", "bytes_sent"};
  s.counter_values = {7, 2, 123456789012};
  s.num_counters = static_cast<int32_t>(s.counter_names.size());
  return s;
}

// ---- Field-by-field comparison (exact: LCM copies the bits). ----

void ExpectSame(const pose2d_t& a, const pose2d_t& b) {
  EXPECT_EQ(a.x_m, b.x_m);
  EXPECT_EQ(a.y_m, b.y_m);
  EXPECT_EQ(a.theta_rad, b.theta_rad);
}

void ExpectSame(const laser_scan_t& a, const laser_scan_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.vehicle_id, b.vehicle_id);
  EXPECT_EQ(a.seq, b.seq);
  EXPECT_EQ(a.angle_min_rad, b.angle_min_rad);
  EXPECT_EQ(a.angle_increment_rad, b.angle_increment_rad);
  EXPECT_EQ(a.range_min_m, b.range_min_m);
  EXPECT_EQ(a.range_max_m, b.range_max_m);
  EXPECT_EQ(a.scan_period_s, b.scan_period_s);
  EXPECT_EQ(a.num_ranges, b.num_ranges);
  EXPECT_EQ(a.ranges_m, b.ranges_m);
  EXPECT_EQ(a.num_intensities, b.num_intensities);
  EXPECT_EQ(a.intensities, b.intensities);
}

void ExpectSame(const odometry_t& a, const odometry_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.vehicle_id, b.vehicle_id);
  ExpectSame(a.pose, b.pose);
  EXPECT_EQ(a.v_mps, b.v_mps);
  EXPECT_EQ(a.omega_radps, b.omega_radps);
}

void ExpectSame(const pose_with_covariance_t& a, const pose_with_covariance_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.vehicle_id, b.vehicle_id);
  ExpectSame(a.pose, b.pose);
  for (int i = 0; i < 9; ++i) EXPECT_EQ(a.covariance[i], b.covariance[i]) << "index " << i;
  EXPECT_EQ(a.map_version, b.map_version);
}

void ExpectSame(const divergence_t& a, const divergence_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.vehicle_id, b.vehicle_id);
  EXPECT_EQ(a.w_avg, b.w_avg);
  EXPECT_EQ(a.w_slow, b.w_slow);
  EXPECT_EQ(a.w_fast, b.w_fast);
  EXPECT_EQ(a.d, b.d);
  EXPECT_EQ(a.state, b.state);
  EXPECT_EQ(a.rotating, b.rotating);
  EXPECT_EQ(a.tempmap_seq, b.tempmap_seq);
}

void ExpectSame(const map_tile_t& a, const map_tile_t& b) {
  EXPECT_EQ(a.tile_x, b.tile_x);
  EXPECT_EQ(a.tile_y, b.tile_y);
  EXPECT_EQ(a.x0_cells, b.x0_cells);
  EXPECT_EQ(a.y0_cells, b.y0_cells);
  EXPECT_EQ(a.width_cells, b.width_cells);
  EXPECT_EQ(a.height_cells, b.height_cells);
  EXPECT_EQ(a.tile_version, b.tile_version);
  EXPECT_EQ(a.codec, b.codec);
  EXPECT_EQ(a.payload_size, b.payload_size);
  EXPECT_EQ(a.payload, b.payload);
  EXPECT_EQ(a.crc32, b.crc32);
}

void ExpectSame(const tempmap_tile_t& a, const tempmap_tile_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.vehicle_id, b.vehicle_id);
  EXPECT_EQ(a.tempmap_seq, b.tempmap_seq);
  EXPECT_EQ(a.tile_index, b.tile_index);
  EXPECT_EQ(a.tile_count, b.tile_count);
  ExpectSame(a.anchor_pose, b.anchor_pose);
  ExpectSame(a.grid_origin, b.grid_origin);
  EXPECT_EQ(a.resolution_m, b.resolution_m);
  EXPECT_EQ(a.width_cells, b.width_cells);
  EXPECT_EQ(a.height_cells, b.height_cells);
  EXPECT_EQ(a.start_utime, b.start_utime);
  EXPECT_EQ(a.end_utime, b.end_utime);
  ExpectSame(a.tile, b.tile);
}

void ExpectSame(const tempmap_ack_t& a, const tempmap_ack_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.vehicle_id, b.vehicle_id);
  EXPECT_EQ(a.tempmap_seq, b.tempmap_seq);
  EXPECT_EQ(a.tile_count, b.tile_count);
  EXPECT_EQ(a.num_received, b.num_received);
  EXPECT_EQ(a.received_tiles, b.received_tiles);
  EXPECT_EQ(a.outcome, b.outcome);
  EXPECT_EQ(a.reason, b.reason);
  EXPECT_EQ(a.map_version, b.map_version);
}

void ExpectSame(const map_delta_t& a, const map_delta_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.base_version, b.base_version);
  EXPECT_EQ(a.new_version, b.new_version);
  EXPECT_EQ(a.tile_index, b.tile_index);
  EXPECT_EQ(a.tile_count, b.tile_count);
  ExpectSame(a.tile, b.tile);
}

void ExpectSame(const map_keyframe_t& a, const map_keyframe_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.version, b.version);
  EXPECT_EQ(a.resolution_m, b.resolution_m);
  EXPECT_EQ(a.width_cells, b.width_cells);
  EXPECT_EQ(a.height_cells, b.height_cells);
  ExpectSame(a.origin, b.origin);
  EXPECT_EQ(a.tile_size_cells, b.tile_size_cells);
  EXPECT_EQ(a.tile_index, b.tile_index);
  EXPECT_EQ(a.tile_count, b.tile_count);
  ExpectSame(a.tile, b.tile);
}

void ExpectSame(const map_request_t& a, const map_request_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.vehicle_id, b.vehicle_id);
  EXPECT_EQ(a.have_version, b.have_version);
  EXPECT_EQ(a.num_tiles, b.num_tiles);
  EXPECT_EQ(a.tiles, b.tiles);
}

void ExpectSame(const line_match_t& a, const line_match_t& b) {
  EXPECT_EQ(a.temp_line_id, b.temp_line_id);
  EXPECT_EQ(a.static_line_id, b.static_line_id);
  EXPECT_EQ(a.distance_diff_px, b.distance_diff_px);
  EXPECT_EQ(a.angle_diff_deg, b.angle_diff_deg);
}

void ExpectSame(const merge_report_t& a, const merge_report_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.vehicle_id, b.vehicle_id);
  EXPECT_EQ(a.tempmap_seq, b.tempmap_seq);
  EXPECT_EQ(a.accepted, b.accepted);
  EXPECT_EQ(a.reason, b.reason);
  EXPECT_EQ(a.dtheta_rad, b.dtheta_rad);
  EXPECT_EQ(a.dx_m, b.dx_m);
  EXPECT_EQ(a.dy_m, b.dy_m);
  EXPECT_EQ(a.score, b.score);
  EXPECT_EQ(a.num_matches, b.num_matches);
  ASSERT_EQ(a.matches.size(), b.matches.size());
  for (size_t i = 0; i < a.matches.size(); ++i) ExpectSame(a.matches[i], b.matches[i]);
  EXPECT_EQ(a.cells_added, b.cells_added);
  EXPECT_EQ(a.cells_removed, b.cells_removed);
  EXPECT_EQ(a.new_version, b.new_version);
}

void ExpectSame(const status_t& a, const status_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.process, b.process);
  EXPECT_EQ(a.software_version, b.software_version);
  EXPECT_EQ(a.map_version, b.map_version);
  EXPECT_EQ(a.state, b.state);
  EXPECT_EQ(a.authenticated, b.authenticated);
  EXPECT_EQ(a.num_counters, b.num_counters);
  EXPECT_EQ(a.counter_names, b.counter_names);
  EXPECT_EQ(a.counter_values, b.counter_values);
}

// ---- The same checks for every type. ----

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

// ---- Length fields: LCM 1.3.1 trusts num_* and never compares it with the vector. ----

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

// ---- Through lcm::LCM, in process (memq://). ----
//
// Handlers are objects subscribed with subscribeFunction() and the object as context, not
// with subscribe(&Class::Method, object): LCM 1.3.1 calls the latter through a pointer to
// member, which GCC 12 miscompiles under -fsanitize=vptr (part of FLEETMAP_SANITIZE's
// -fsanitize=undefined): the handler runs with this == nullptr and crashes.

class ScanHandler {
 public:
  static void Dispatch(const lcm::ReceiveBuffer* /*rbuf*/, const std::string& channel,
                       const laser_scan_t* msg, ScanHandler* handler) {
    handler->OnScan(channel, *msg);
  }
  void OnScan(const std::string& channel, const laser_scan_t& msg) {
    channels.push_back(channel);
    scans.push_back(msg);
  }
  std::vector<std::string> channels;
  std::vector<laser_scan_t> scans;
};

TEST(LcmTypesTest, MemqPublishSubscribeRoundTrip) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  ScanHandler handler;
  ASSERT_NE(lcm.subscribeFunction("SCAN_.*", &ScanHandler::Dispatch, &handler), nullptr);
  const laser_scan_t sent = MakeSample<laser_scan_t>();
  ASSERT_EQ(lcm.publish("SCAN_agv_1", &sent), 0);
  ASSERT_GT(lcm.handleTimeout(1000), 0);
  ASSERT_EQ(handler.scans.size(), 1u);
  EXPECT_EQ(handler.channels[0], "SCAN_agv_1");
  ExpectSame(sent, handler.scans[0]);
}

// A typed subscription decodes inside LCM's C callback: a decode() that throws escapes
// handleTimeout() and leaves the instance unusable (the next handle asserts `!lcm->in_handle`
// in lcm.c and aborts). Outside data must therefore be subscribed raw and decoded by the
// handler, catching exceptions.
class RawScanHandler {
 public:
  static void Dispatch(const lcm::ReceiveBuffer* rbuf, const std::string& /*channel*/,
                       RawScanHandler* handler) {
    handler->OnRaw(*rbuf);
  }
  void OnRaw(const lcm::ReceiveBuffer& rbuf) {
    laser_scan_t msg;
    try {
      if (msg.decode(rbuf.data, 0, static_cast<int>(rbuf.data_size)) < 0) {
        ++rejected;
        return;
      }
    } catch (const std::exception&) {
      ++rejected;
      return;
    }
    scans.push_back(msg);
  }
  int rejected = 0;
  std::vector<laser_scan_t> scans;
};

TEST(LcmTypesTest, RawSubscriptionSurvivesMalformedMessage) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  RawScanHandler handler;
  ASSERT_NE(lcm.subscribeFunction("SCAN_.*", &RawScanHandler::Dispatch, &handler), nullptr);
  Bytes bad = Encode(MakeSample<laser_scan_t>());
  bad[16] = bad[17] = bad[18] = bad[19] = 0;  // vehicle_id length 0: decode() throws
  ASSERT_EQ(lcm.publish("SCAN_agv_1", bad.data(), static_cast<unsigned>(bad.size())), 0);
  const laser_scan_t good = MakeSample<laser_scan_t>();
  ASSERT_EQ(lcm.publish("SCAN_agv_1", &good), 0);
  ASSERT_GT(lcm.handleTimeout(1000), 0);
  ASSERT_GT(lcm.handleTimeout(1000), 0);
  EXPECT_EQ(handler.rejected, 1);
  ASSERT_EQ(handler.scans.size(), 1u);
  ExpectSame(good, handler.scans[0]);
}

}  // namespace
}  // namespace fleetmap
