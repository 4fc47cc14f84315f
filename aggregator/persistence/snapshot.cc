#include "aggregator/persistence/snapshot.h"

#include <cstring>

#include "core/io/byte_io.h"
#include "core/io/crc32.h"
#include "core/io/file_io.h"

namespace fleetmap::aggregator {
namespace {

constexpr uint8_t kMagic[4] = {'F', 'M', 'S', '1'};

core::Result<SnapshotContents> DecodeBody(core::ByteReader& r) {
  SnapshotContents s;
  s.version = r.U64();
  s.static_fingerprint = r.U32();
  s.map_fingerprint = r.U32();
  const uint32_t count = r.U32();
  if (r.failed() || count > r.remaining() / 4) return core::DataLoss("snapshot: truncated header");
  for (uint32_t i = 0; i < count; ++i) {
    const uint32_t length = r.U32();
    const uint8_t* payload = r.Bytes(length);
    if (!payload) return core::DataLoss("snapshot: truncated commit");
    auto commit = DecodeCommit(payload, length);
    if (!commit.ok()) return commit.status().WithContext("snapshot commit " + std::to_string(i));
    s.commits.push_back(std::move(commit).value());
  }
  return s;
}

}  // namespace

uint32_t MapFingerprint(const core::OccupancyGrid& grid) {
  std::vector<uint8_t> bytes;
  core::ByteWriter w(bytes);
  const core::GridGeometry& g = grid.geometry();
  w.F64(g.resolution_m());
  w.I32(g.width());
  w.I32(g.height());
  w.F64(g.origin().x_m);
  w.F64(g.origin().y_m);
  w.F64(g.origin().theta_rad);
  w.Bytes(reinterpret_cast<const uint8_t*>(grid.cells().data()),
          grid.cells().size() * sizeof(float));
  return core::Crc32(bytes.data(), bytes.size());
}

std::vector<uint8_t> EncodeSnapshot(const CurrentMapStore& store) {
  std::vector<uint8_t> out(kMagic, kMagic + 4);
  core::ByteWriter w(out);
  w.U32(kSnapshotFormatVersion);
  w.U64(store.version());
  w.U32(MapFingerprint(store.static_map()));
  w.U32(MapFingerprint(store.current_map()));
  const auto& commits = store.provenance().commits();
  w.U32(static_cast<uint32_t>(commits.size()));
  for (const MergeCommit& c : commits) {
    const std::vector<uint8_t> payload = EncodeCommit(c);
    w.U32(static_cast<uint32_t>(payload.size()));
    w.Bytes(payload.data(), payload.size());
  }
  w.U32(core::Crc32(out.data(), out.size()));
  return out;
}

core::Result<SnapshotContents> DecodeSnapshot(const uint8_t* data, size_t size) {
  if (size < 12 || std::memcmp(data, kMagic, 4) != 0)
    return core::DataLoss("not a fleetmap snapshot");
  core::ByteReader trailer(data + size - 4, 4);
  if (core::Crc32(data, size - 4) != trailer.U32()) return core::DataLoss("snapshot CRC mismatch");
  core::ByteReader r(data + 4, size - 8);
  const uint32_t format = r.U32();
  if (format != kSnapshotFormatVersion)
    return core::Unimplemented("snapshot format version " + std::to_string(format));
  auto contents = DecodeBody(r);
  if (contents.ok() && r.remaining() != 0) return core::DataLoss("snapshot: trailing bytes");
  return contents;
}

core::Status WriteSnapshot(const CurrentMapStore& store, const std::string& path) {
  const std::vector<uint8_t> bytes = EncodeSnapshot(store);
  return core::WriteFileAtomically(
      path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

core::Result<SnapshotContents> ReadSnapshot(const std::string& path, int64_t max_bytes) {
  std::string bytes;
  FLEETMAP_ASSIGN_OR_RETURN(bytes, core::ReadFileBytes(path, max_bytes));
  auto contents = DecodeSnapshot(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  if (!contents.ok()) return contents.status().WithContext(path);
  return contents;
}

}  // namespace fleetmap::aggregator
