// Field-by-field comparison of two messages of a generated LCM type (package fleetmap):
// exact, since LCM copies the bits, and one failure per field that differs.
#pragma once

#include <gtest/gtest.h>

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

inline void ExpectSame(const pose2d_t& a, const pose2d_t& b) {
  EXPECT_EQ(a.x_m, b.x_m);
  EXPECT_EQ(a.y_m, b.y_m);
  EXPECT_EQ(a.theta_rad, b.theta_rad);
}

inline void ExpectSame(const laser_scan_t& a, const laser_scan_t& b) {
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

inline void ExpectSame(const odometry_t& a, const odometry_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.vehicle_id, b.vehicle_id);
  ExpectSame(a.pose, b.pose);
  EXPECT_EQ(a.v_mps, b.v_mps);
  EXPECT_EQ(a.omega_radps, b.omega_radps);
}

inline void ExpectSame(const pose_with_covariance_t& a, const pose_with_covariance_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.vehicle_id, b.vehicle_id);
  ExpectSame(a.pose, b.pose);
  for (int i = 0; i < 9; ++i) EXPECT_EQ(a.covariance[i], b.covariance[i]) << "index " << i;
  EXPECT_EQ(a.map_version, b.map_version);
}

inline void ExpectSame(const divergence_t& a, const divergence_t& b) {
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

inline void ExpectSame(const map_tile_t& a, const map_tile_t& b) {
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

inline void ExpectSame(const tempmap_tile_t& a, const tempmap_tile_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.vehicle_id, b.vehicle_id);
  EXPECT_EQ(a.tempmap_seq, b.tempmap_seq);
  EXPECT_EQ(a.tile_index, b.tile_index);
  EXPECT_EQ(a.tile_count, b.tile_count);
  ExpectSame(a.anchor_pose, b.anchor_pose);
  EXPECT_EQ(a.has_anchor_covariance, b.has_anchor_covariance);
  for (int i = 0; i < 9; ++i)
    EXPECT_EQ(a.anchor_covariance[i], b.anchor_covariance[i]) << "index " << i;
  ExpectSame(a.grid_origin, b.grid_origin);
  EXPECT_EQ(a.resolution_m, b.resolution_m);
  EXPECT_EQ(a.width_cells, b.width_cells);
  EXPECT_EQ(a.height_cells, b.height_cells);
  EXPECT_EQ(a.start_utime, b.start_utime);
  EXPECT_EQ(a.end_utime, b.end_utime);
  ExpectSame(a.tile, b.tile);
}

inline void ExpectSame(const tempmap_ack_t& a, const tempmap_ack_t& b) {
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

inline void ExpectSame(const map_delta_t& a, const map_delta_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.base_version, b.base_version);
  EXPECT_EQ(a.new_version, b.new_version);
  EXPECT_EQ(a.tile_index, b.tile_index);
  EXPECT_EQ(a.tile_count, b.tile_count);
  ExpectSame(a.tile, b.tile);
}

inline void ExpectSame(const map_keyframe_t& a, const map_keyframe_t& b) {
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

inline void ExpectSame(const map_request_t& a, const map_request_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.vehicle_id, b.vehicle_id);
  EXPECT_EQ(a.have_version, b.have_version);
  EXPECT_EQ(a.num_tiles, b.num_tiles);
  EXPECT_EQ(a.tiles, b.tiles);
}

inline void ExpectSame(const line_match_t& a, const line_match_t& b) {
  EXPECT_EQ(a.temp_line_id, b.temp_line_id);
  EXPECT_EQ(a.static_line_id, b.static_line_id);
  EXPECT_EQ(a.distance_diff_px, b.distance_diff_px);
  EXPECT_EQ(a.angle_diff_deg, b.angle_diff_deg);
}

inline void ExpectSame(const merge_report_t& a, const merge_report_t& b) {
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

inline void ExpectSame(const status_t& a, const status_t& b) {
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

}  // namespace fleetmap::lcmtypes::testing
