#include "core/codec/cell_packing.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

namespace fleetmap::core {
namespace {

int8_t Quantize(float log_odds) {
  const float q = std::round(log_odds / kLogOddsQuantum);
  return static_cast<int8_t>(std::clamp(q, -127.0f, 127.0f));
}

}  // namespace

bool IsValidCellPacking(uint8_t code) { return code <= uint8_t(CellPacking::kLogOddsInt8); }

const char* CellPackingName(CellPacking packing) {
  switch (packing) {
    case CellPacking::kTriState2Bit:
      return "tristate2";
    case CellPacking::kTriState8Bit:
      return "tristate8";
    case CellPacking::kLogOddsInt8:
      return "logodds8";
  }
  return "invalid";
}

int64_t PackedSize(CellPacking packing, int64_t num_cells) {
  return packing == CellPacking::kTriState2Bit ? (num_cells + 3) / 4 : num_cells;
}

std::vector<uint8_t> PackCells(const OccupancyGrid& grid, const CellWindow& window,
                               CellPacking packing, const OccupancyThresholds& thresholds) {
  assert(grid.geometry().Contains(window));
  std::vector<uint8_t> out(static_cast<size_t>(PackedSize(packing, window.num_cells())), 0);
  const TriStateClassifier classify(thresholds);
  size_t i = 0;  // cell number inside the window
  // Row by row with the packing decided outside the inner loop: this runs over whole maps
  // for every keyframe and delta.
  for (int y = window.y0; y < window.y0 + window.height; ++y) {
    const float* row = grid.cells().data() + grid.geometry().Index({window.x0, y});
    switch (packing) {
      case CellPacking::kTriState2Bit:
        for (int x = 0; x < window.width; ++x, ++i)
          out[i >> 2] |= static_cast<uint8_t>(uint8_t(classify(row[x])) << (2 * (i & 3)));
        break;
      case CellPacking::kTriState8Bit:
        for (int x = 0; x < window.width; ++x, ++i) out[i] = uint8_t(classify(row[x]));
        break;
      case CellPacking::kLogOddsInt8:
        for (int x = 0; x < window.width; ++x, ++i) out[i] = static_cast<uint8_t>(Quantize(row[x]));
        break;
    }
  }
  return out;
}

Result<PackedValues> UnpackCells(const uint8_t* packed, int64_t packed_size, CellPacking packing,
                                 int64_t num_cells) {
  if (packed_size != PackedSize(packing, num_cells)) {
    return DataLoss("packed size " + std::to_string(packed_size) + " does not fit " +
                    std::to_string(num_cells) + " cells");
  }
  PackedValues values(static_cast<size_t>(num_cells));
  if (packing == CellPacking::kTriState2Bit) {
    for (int64_t i = 0; i < num_cells; ++i)
      values[i] = int8_t((packed[i >> 2] >> (2 * (i & 3))) & 3);
  } else {
    std::memcpy(values.data(), packed, static_cast<size_t>(num_cells));
  }
  // Reject codes no encoder writes, so corrupt input never becomes a plausible map.
  const int8_t lowest = packing == CellPacking::kLogOddsInt8 ? -127 : 0;
  const int8_t highest = packing == CellPacking::kLogOddsInt8 ? 127 : 2;
  for (int64_t i = 0; i < num_cells; ++i) {
    if (values[i] < lowest || values[i] > highest) {
      return DataLoss(std::string(packing == CellPacking::kLogOddsInt8
                                      ? "log-odds quantum "
                                      : "invalid tri-state code ") +
                      std::to_string(values[i]) + " at cell " + std::to_string(i));
    }
  }
  return values;
}

void WriteCells(const PackedValues& values, CellPacking packing, const CellWindow& window,
                OccupancyGrid& grid) {
  assert(grid.geometry().Contains(window));
  assert(static_cast<int64_t>(values.size()) == window.num_cells());
  float canonical[3];
  for (int s = 0; s < 3; ++s) canonical[s] = grid.CanonicalLogOdds(static_cast<CellState>(s));
  const LogOddsLimits& limits = grid.limits();
  const int8_t* v = values.data();
  for (int y = window.y0; y < window.y0 + window.height; ++y) {
    float* row = grid.mutable_cells().data() + grid.geometry().Index({window.x0, y});
    if (packing == CellPacking::kLogOddsInt8) {
      for (int x = 0; x < window.width; ++x, ++v)
        row[x] = std::clamp(*v * kLogOddsQuantum, limits.min_log_odds, limits.max_log_odds);
    } else {
      for (int x = 0; x < window.width; ++x, ++v) row[x] = canonical[*v];
    }
  }
}

}  // namespace fleetmap::core
