#include "lcmtypes/transport_convert.h"

#include <cmath>

#include "core/io/crc32.h"
#include "core/odometry.h"
#include "lcmtypes/convert.h"

namespace fleetmap::lcmtypes {
namespace {

constexpr size_t kMaxTileBytes = 64 * 1024;  // a 64 x 64 int8 tile is 4 KB before zstd

fleetmap::map_tile_t TileMessage(const core::TileIndex& index, const std::vector<uint8_t>& frame) {
  fleetmap::map_tile_t m;
  m.tile_x = index.tx;
  m.tile_y = index.ty;
  m.x0_cells = m.y0_cells = m.width_cells = m.height_cells = 0;
  m.tile_version = 0;
  m.codec = 0;
  if (frame.size() >= core::kCodecHeaderBytes) {
    m.codec = static_cast<int8_t>((frame[5] << 4) | frame[6]);  // packing, compression bytes
    auto read = [&](size_t at) {
      return int32_t(frame[at]) | int32_t(frame[at + 1]) << 8 | int32_t(frame[at + 2]) << 16 |
             int32_t(frame[at + 3]) << 24;
    };
    m.x0_cells = read(8), m.y0_cells = read(12), m.width_cells = read(16),
    m.height_cells = read(20);
  }
  m.payload.assign(frame.begin(), frame.end());
  m.payload_size = static_cast<int32_t>(m.payload.size());
  m.crc32 = static_cast<int32_t>(core::Crc32(frame.data(), frame.size()));
  return m;
}

// The frame of a tile message, checked against its CRC and its size limit.
core::Result<std::vector<uint8_t>> TileFrame(const fleetmap::map_tile_t& m,
                                             core::TileIndex& index) {
  if (m.payload_size != static_cast<int32_t>(m.payload.size()) ||
      m.payload.size() > kMaxTileBytes) {
    return core::DataLoss("tile payload size is wrong or too large");
  }
  if (static_cast<uint32_t>(m.crc32) != core::Crc32(m.payload.data(), m.payload.size())) {
    return core::DataLoss("tile payload CRC mismatch");
  }
  index = {m.tile_x, m.tile_y};
  return m.payload;
}

}  // namespace

double SnapResolution(float resolution_m) { return std::round(double{resolution_m} * 1e6) / 1e6; }

fleetmap::tempmap_tile_t ToMessage(const core::TempMapTile& t, int64_t utime) {
  fleetmap::tempmap_tile_t m;
  m.utime = utime;
  m.vehicle_id = t.vehicle_id;
  m.tempmap_seq = t.sequence;
  m.tile_index = t.index;
  m.tile_count = t.count;
  m.anchor_pose = ToMessage(t.anchor_in_map);
  m.has_anchor_covariance = t.anchor_covariance.has_value();
  ToRowMajor(t.anchor_covariance.value_or(Eigen::Matrix3d::Zero()), m.anchor_covariance);
  m.grid_origin = ToMessage(t.grid_origin);
  m.resolution_m = static_cast<float>(t.resolution_m);
  m.width_cells = t.width_cells;
  m.height_cells = t.height_cells;
  m.start_utime = ToUtime(t.start_s);
  m.end_utime = ToUtime(t.end_s);
  m.tile = TileMessage(t.tile, t.frame);
  return m;
}

core::Result<core::TempMapTile> FromMessage(const fleetmap::tempmap_tile_t& m) {
  core::TempMapTile t;
  FLEETMAP_RETURN_IF_ERROR(CheckVehicleId(m.vehicle_id));
  t.vehicle_id = m.vehicle_id;
  t.sequence = m.tempmap_seq;
  t.index = m.tile_index;
  t.count = m.tile_count;
  t.anchor_in_map = FromMessage(m.anchor_pose);
  t.grid_origin = FromMessage(m.grid_origin);
  if (!t.anchor_in_map.IsFinite() || !t.grid_origin.IsFinite())
    return core::InvalidArgument("temporary map anchor or grid origin is not finite");
  if (m.has_anchor_covariance) {
    const Eigen::Matrix3d c = FromRowMajor(m.anchor_covariance);
    FLEETMAP_RETURN_IF_ERROR(core::ValidatePoseCovariance(c).WithContext("temporary map anchor"));
    t.anchor_covariance = c;
  }
  t.resolution_m = SnapResolution(m.resolution_m);
  t.width_cells = m.width_cells;
  t.height_cells = m.height_cells;
  t.start_s = FromUtime(m.start_utime);
  t.end_s = FromUtime(m.end_utime);
  FLEETMAP_ASSIGN_OR_RETURN(t.frame, TileFrame(m.tile, t.tile));
  return t;  // the assembler checks the rest against the map's layout
}

fleetmap::map_keyframe_t ToMessage(const core::KeyframeTile& k, int64_t utime) {
  fleetmap::map_keyframe_t m;
  m.utime = utime;
  m.version = k.version;
  m.resolution_m = static_cast<float>(k.geometry.resolution_m());
  m.width_cells = k.geometry.width();
  m.height_cells = k.geometry.height();
  m.origin.x_m = k.geometry.origin().x_m;
  m.origin.y_m = k.geometry.origin().y_m;
  m.origin.theta_rad = k.geometry.origin().theta_rad;
  m.tile_size_cells = k.tile_size_cells;
  m.tile_index = k.index;
  m.tile_count = k.count;
  m.tile = TileMessage(k.tile, k.frame);
  m.tile.tile_version = k.version;
  return m;
}

core::Result<core::KeyframeTile> FromMessage(const fleetmap::map_keyframe_t& m) {
  core::KeyframeTile k;
  k.version = m.version;
  k.geometry = core::GridGeometry(SnapResolution(m.resolution_m), m.width_cells, m.height_cells,
                                  core::Pose2(m.origin.x_m, m.origin.y_m, m.origin.theta_rad));
  FLEETMAP_RETURN_IF_ERROR(k.geometry.Validate().WithContext("keyframe"));
  k.tile_size_cells = m.tile_size_cells;
  k.index = m.tile_index;
  k.count = m.tile_count;
  FLEETMAP_ASSIGN_OR_RETURN(k.frame, TileFrame(m.tile, k.tile));
  return k;  // the replica checks index, count and window
}

fleetmap::map_delta_t ToMessage(const core::DeltaTile& d, int64_t utime) {
  fleetmap::map_delta_t m;
  m.utime = utime;
  m.base_version = d.base_version;
  m.new_version = d.base_version + 1;
  m.tile_index = d.index;
  m.tile_count = d.count;
  m.tile = TileMessage(d.tile, d.frame);
  m.tile.tile_version = m.new_version;
  return m;
}

core::Result<core::DeltaTile> FromMessage(const fleetmap::map_delta_t& m) {
  if (int64_t{m.new_version} != int64_t{m.base_version} + 1)  // no overflow at INT32_MAX
    return core::DataLoss("a delta must advance one version");
  core::DeltaTile d;
  d.base_version = m.base_version;
  d.index = m.tile_index;
  d.count = m.tile_count;
  FLEETMAP_ASSIGN_OR_RETURN(d.frame, TileFrame(m.tile, d.tile));
  return d;
}

}  // namespace fleetmap::lcmtypes
