// Every generated LCM type (package fleetmap) with a sample message, and its encoding, for
// the tests of what LCM's generated code does with good and bad bytes. A sample sets every
// field to a distinct non-default value and every array non-empty, so that a decode that
// drops or zero-fills a field shows.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
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

namespace fleetmap::lcmtypes::testing {

using Bytes = std::vector<uint8_t>;

// The whole encoding; a short encode() fails the test.
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

// The sample of type T: one specialisation per generated type follows.
template <typename T>
T MakeSample();

template <>
inline pose2d_t MakeSample<pose2d_t>() {
  pose2d_t p;
  p.x_m = 12.5;
  p.y_m = -3.25;
  p.theta_rad = 1.0471975511965976;
  return p;
}

template <>
inline laser_scan_t MakeSample<laser_scan_t>() {
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
inline odometry_t MakeSample<odometry_t>() {
  odometry_t o;
  o.utime = 1700000000200000;
  o.vehicle_id = "agv_2";
  o.pose = MakeSample<pose2d_t>();
  o.v_mps = 0.75;
  o.omega_radps = -0.125;
  return o;
}

template <>
inline pose_with_covariance_t MakeSample<pose_with_covariance_t>() {
  pose_with_covariance_t p;
  p.utime = 1700000000300000;
  p.vehicle_id = "agv_3";
  p.pose = MakeSample<pose2d_t>();
  for (int i = 0; i < 9; ++i) p.covariance[i] = 0.01 * (i + 1);
  p.map_version = 17;
  return p;
}

template <>
inline divergence_t MakeSample<divergence_t>() {
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
inline map_tile_t MakeSample<map_tile_t>() {
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
inline tempmap_tile_t MakeSample<tempmap_tile_t>() {
  tempmap_tile_t t;
  t.utime = 1700000000500000;
  t.vehicle_id = "agv_5";
  t.tempmap_seq = 12;
  t.tile_index = 2;
  t.tile_count = 6;
  t.anchor_pose = MakeSample<pose2d_t>();
  // 2 cm in x and y, correlated by 0.25; 1 degree in heading.
  t.has_anchor_covariance = true;
  const double c[9] = {4e-4, 1e-4, 0.0, 1e-4, 4e-4, 0.0, 0.0, 0.0, 3.05e-4};
  for (int i = 0; i < 9; ++i) t.anchor_covariance[i] = c[i];
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
inline tempmap_ack_t MakeSample<tempmap_ack_t>() {
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
inline map_delta_t MakeSample<map_delta_t>() {
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
inline map_keyframe_t MakeSample<map_keyframe_t>() {
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
inline map_request_t MakeSample<map_request_t>() {
  map_request_t r;
  r.utime = 1700000000900000;
  r.vehicle_id = "agv_7";
  r.have_version = 20;
  r.tiles = {5, 6, 230};
  r.num_tiles = static_cast<int32_t>(r.tiles.size());
  return r;
}

template <>
inline line_match_t MakeSample<line_match_t>() {
  line_match_t m;
  m.temp_line_id = 4;
  m.static_line_id = 17;
  m.distance_diff_px = 1.5;
  m.angle_diff_deg = -0.75;
  return m;
}

template <>
inline merge_report_t MakeSample<merge_report_t>() {
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
inline status_t MakeSample<status_t>() {
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

}  // namespace fleetmap::lcmtypes::testing
