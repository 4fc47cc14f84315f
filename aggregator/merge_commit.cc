#include "aggregator/merge_commit.h"

#include <cmath>
#include <limits>

#include "core/io/byte_io.h"

namespace fleetmap::aggregator {
namespace {

constexpr size_t kChangeBytes = 5;

bool AllFinite(std::initializer_list<double> values) {
  for (double v : values)
    if (!std::isfinite(v)) return false;
  return true;
}

core::Status CheckChanges(const std::vector<CellChange>& changes) {
  for (size_t i = 0; i < changes.size(); ++i) {
    if (!IsValidCellChangeKind(static_cast<uint8_t>(changes[i].kind)))
      return core::DataLoss("commit: unknown cell change kind");
    if (i > 0 && changes[i].cell <= changes[i - 1].cell)
      return core::DataLoss("commit: cell changes not in ascending order");
  }
  return core::OkStatus();
}

}  // namespace

bool IsValidCellChangeKind(uint8_t code) { return code >= 1 && code <= 5; }

const char* CellChangeKindName(CellChangeKind kind) {
  switch (kind) {
    case CellChangeKind::kAdded:
      return "added";
    case CellChangeKind::kRemoved:
      return "removed";
    case CellChangeKind::kCandidate:
      return "candidate";
    case CellChangeKind::kCandidateDropped:
      return "candidate_dropped";
    case CellChangeKind::kCandidateWatched:
      return "candidate_watched";
  }
  return "unknown";
}

std::vector<uint8_t> EncodeCommit(const MergeCommit& c) {
  std::vector<uint8_t> out;
  out.reserve(80 + c.source.vehicle_id.size() + c.changes.size() * kChangeBytes);
  core::ByteWriter w(out);
  w.U8(kCommitFormatVersion);
  w.U64(c.version);
  w.U32(static_cast<uint32_t>(c.source.vehicle_id.size()));
  w.Bytes(reinterpret_cast<const uint8_t*>(c.source.vehicle_id.data()), c.source.vehicle_id.size());
  w.I32(c.source.tempmap_sequence);
  for (double v : {c.source.tempmap_start_s, c.source.tempmap_end_s, c.source.merged_s,
                   c.correction.x_m, c.correction.y_m, c.correction.theta_rad}) {
    w.F64(v);
  }
  w.U32(static_cast<uint32_t>(c.changes.size()));
  for (const CellChange& change : c.changes) {
    w.U32(static_cast<uint32_t>(change.cell));
    w.U8(static_cast<uint8_t>(change.kind));
  }
  return out;
}

core::Result<MergeCommit> DecodeCommit(const uint8_t* data, size_t size) {
  core::ByteReader r(data, size);
  const uint8_t format = r.U8();
  if (!r.failed() && format > kCommitFormatVersion)
    return core::Unimplemented("commit format version " + std::to_string(format));
  MergeCommit c;
  c.version = r.U64();
  const uint32_t id_bytes = r.U32();
  if (r.failed() || format != kCommitFormatVersion || id_bytes == 0 ||
      id_bytes > kMaxVehicleIdBytes)
    return core::DataLoss("commit: bad header");
  const uint8_t* id = r.Bytes(id_bytes);
  if (id) c.source.vehicle_id.assign(reinterpret_cast<const char*>(id), id_bytes);
  c.source.tempmap_sequence = r.I32();
  c.source.tempmap_start_s = r.F64();
  c.source.tempmap_end_s = r.F64();
  c.source.merged_s = r.F64();
  c.correction.x_m = r.F64();
  c.correction.y_m = r.F64();
  c.correction.theta_rad = r.F64();
  const uint32_t count = r.U32();
  if (r.failed() || count > r.remaining() / kChangeBytes)
    return core::DataLoss("commit: truncated");
  if (!AllFinite({c.source.tempmap_start_s, c.source.tempmap_end_s, c.source.merged_s}) ||
      !c.correction.IsFinite()) {
    return core::DataLoss("commit: non-finite time or correction");
  }
  c.changes.resize(count);
  for (CellChange& change : c.changes) {
    change.cell = r.U32();
    change.kind = static_cast<CellChangeKind>(r.U8());
  }
  if (r.failed() || r.remaining() != 0) return core::DataLoss("commit: wrong payload length");
  FLEETMAP_RETURN_IF_ERROR(CheckChanges(c.changes));
  return c;
}

}  // namespace fleetmap::aggregator
