#include "core/map/temp_map_file.h"

#include <cstring>
#include <string>

#include "core/codec/map_codec.h"
#include "core/io/byte_io.h"
#include "core/io/crc32.h"
#include "core/io/file_io.h"

namespace fleetmap::core {
namespace {

constexpr uint8_t kMagic[4] = {'F', 'M', 'T', 'M'};
// Version 2 keeps the anchor and the grid's origin in the map's frame apart (the aggregator
// turns a map about its anchor, and the anchor's covariance is the vehicle's) and adds the
// covariance; files of version 1 (the placed corner only) still read, without it.
constexpr uint8_t kVersion = 2;
constexpr uint8_t kVersionWithoutCovariance = 1;
constexpr size_t kMaxIdBytes = 64;
constexpr int64_t kMaxFileBytes = 256 << 20;

}  // namespace

std::vector<uint8_t> EncodeTempMap(const TempMap& map) {
  std::vector<uint8_t> out;
  ByteWriter w(out);
  w.Bytes(kMagic, 4);
  w.U8(kVersion);
  w.U32(static_cast<uint32_t>(map.vehicle_id.size()));
  w.Bytes(reinterpret_cast<const uint8_t*>(map.vehicle_id.data()), map.vehicle_id.size());
  w.I32(map.sequence);
  for (const Pose2& p : {map.anchor_in_map, map.grid.geometry().origin()}) {
    w.F64(p.x_m);
    w.F64(p.y_m);
    w.F64(p.theta_rad);
  }
  w.F64(map.grid.geometry().resolution_m());
  w.F64(map.start_s);
  w.F64(map.end_s);
  w.U8(map.anchor_covariance ? 1 : 0);
  if (map.anchor_covariance)
    for (int i = 0; i < 3; ++i)
      for (int j = i; j < 3; ++j) w.F64((*map.anchor_covariance)(i, j));
  CodecOptions codec;
  codec.packing = CellPacking::kLogOddsInt8;
  const std::vector<uint8_t> frame =
      EncodeWindow(map.grid, map.grid.geometry().full_window(), codec);
  w.U32(static_cast<uint32_t>(frame.size()));
  w.Bytes(frame.data(), frame.size());
  w.U32(Crc32(out.data(), out.size()));
  return out;
}

Result<TempMap> DecodeTempMap(const uint8_t* data, size_t size) {
  if (size < 4 + 1 + 4 + 4) return DataLoss("temporary map file is truncated");
  if (Crc32(data, size - 4) != ByteReader(data + size - 4, 4).U32()) {
    return DataLoss("temporary map file CRC mismatch");
  }
  ByteReader r(data, size - 4);
  if (std::memcmp(r.Bytes(4), kMagic, 4) != 0) return DataLoss("not a temporary map file");
  const uint8_t version = r.U8();
  if (version != kVersion && version != kVersionWithoutCovariance)
    return Unimplemented("temporary map file version " + std::to_string(version) +
                         " not supported");
  const uint32_t id_size = r.U32();
  if (id_size == 0 || id_size > kMaxIdBytes) return DataLoss("vehicle id length out of range");
  const uint8_t* id = r.Bytes(id_size);
  if (!id) return DataLoss("temporary map file is truncated");
  TempMap map;
  map.vehicle_id.assign(reinterpret_cast<const char*>(id), id_size);
  map.sequence = r.I32();
  // Version 1: the placed corner, the grid's origin at the anchor.
  const double x = r.F64(), y = r.F64(), theta = r.F64();
  map.anchor_in_map = Pose2(x, y, theta);
  Pose2 grid_origin;
  if (version >= kVersion) {
    const double gx = r.F64(), gy = r.F64(), gtheta = r.F64();
    grid_origin = Pose2(gx, gy, gtheta);
  }
  const double res = r.F64();
  map.start_s = r.F64();
  map.end_s = r.F64();
  if (version >= kVersion) {
    const uint8_t has_covariance = r.U8();
    if (has_covariance > 1) return DataLoss("temporary map file: bad covariance flag");
    if (has_covariance) {
      Eigen::Matrix3d c;
      for (int i = 0; i < 3; ++i)
        for (int j = i; j < 3; ++j) c(i, j) = c(j, i) = r.F64();
      map.anchor_covariance = c;
    }
  }
  const uint32_t frame_size = r.U32();
  const uint8_t* frame = r.Bytes(frame_size);
  if (r.failed() || !frame || r.remaining() != 0)
    return DataLoss("temporary map file is truncated or padded");
  auto decoded = DecodeFrame(frame, frame_size);
  if (!decoded.ok()) return decoded.status().WithContext("temporary map cells");
  const GridGeometry g(res, decoded->window.width, decoded->window.height, grid_origin);
  FLEETMAP_RETURN_IF_ERROR(g.Validate().WithContext("temporary map file"));
  map.grid = OccupancyGrid(g);
  FLEETMAP_RETURN_IF_ERROR(ApplyFrame(*decoded, map.grid));
  FLEETMAP_RETURN_IF_ERROR(map.Validate());
  return map;
}

Status SaveTempMap(const TempMap& map, const std::string& path, Durability durability) {
  const std::vector<uint8_t> bytes = EncodeTempMap(map);
  return WriteFileAtomically(
      path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
      durability);
}

Result<TempMap> LoadTempMap(const std::string& path) {
  auto bytes = ReadFileBytes(path, kMaxFileBytes);
  if (!bytes.ok()) return bytes.status();
  auto map = DecodeTempMap(reinterpret_cast<const uint8_t*>(bytes->data()), bytes->size());
  if (!map.ok()) return map.status().WithContext(path);
  return map;
}

}  // namespace fleetmap::core
