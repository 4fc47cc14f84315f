#include "core/cell_packing.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace fleetmap::core {
namespace {

int8_t Quantize(float log_odds) {
  const float q = std::round(log_odds / kLogOddsQuantum);
  return static_cast<int8_t>(std::clamp(q, -127.0f, 127.0f));
}

template <typename CellFn>
void ForEachCell(const CellWindow& w, CellFn fn) {
  for (int y = w.y0; y < w.y0 + w.height; ++y)
    for (int x = w.x0; x < w.x0 + w.width; ++x) fn(CellIndex{x, y});
}

}  // namespace

bool IsValidCellPacking(uint8_t code) { return code <= uint8_t(CellPacking::kLogOddsInt8); }

const char* CellPackingName(CellPacking packing) {
  switch (packing) {
    case CellPacking::kTriState2Bit: return "tristate2";
    case CellPacking::kTriState8Bit: return "tristate8";
    case CellPacking::kLogOddsInt8: return "logodds8";
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
  const std::vector<float>& cells = grid.cells();
  size_t i = 0;
  ForEachCell(window, [&](const CellIndex& c) {
    const float l = cells[grid.geometry().Index(c)];
    switch (packing) {
      case CellPacking::kTriState2Bit:
        out[i / 4] |= static_cast<uint8_t>(uint8_t(classify(l)) << (2 * (i % 4)));
        break;
      case CellPacking::kTriState8Bit: out[i] = uint8_t(classify(l)); break;
      case CellPacking::kLogOddsInt8: out[i] = static_cast<uint8_t>(Quantize(l)); break;
    }
    ++i;
  });
  return out;
}

Result<PackedValues> UnpackCells(const uint8_t* packed, int64_t packed_size, CellPacking packing,
                                 int64_t num_cells) {
  if (packed_size != PackedSize(packing, num_cells)) {
    return DataLoss("packed size " + std::to_string(packed_size) + " does not fit " +
                    std::to_string(num_cells) + " cells");
  }
  PackedValues values(static_cast<size_t>(num_cells));
  for (int64_t i = 0; i < num_cells; ++i) {
    int v;
    if (packing == CellPacking::kTriState2Bit) {
      v = (packed[i / 4] >> (2 * (i % 4))) & 3;
    } else {
      v = static_cast<int8_t>(packed[i]);
    }
    if (packing != CellPacking::kLogOddsInt8 && (v < 0 || v > 2)) {
      return DataLoss("invalid tri-state code " + std::to_string(v) + " at cell " +
                      std::to_string(i));
    }
    if (packing == CellPacking::kLogOddsInt8 && v == -128) {
      return DataLoss("log-odds quantum -128 is never written (cell " + std::to_string(i) + ")");
    }
    values[static_cast<size_t>(i)] = static_cast<int8_t>(v);
  }
  return values;
}

void WriteCells(const PackedValues& values, CellPacking packing, const CellWindow& window,
                OccupancyGrid& grid) {
  assert(grid.geometry().Contains(window));
  assert(static_cast<int64_t>(values.size()) == window.num_cells());
  size_t i = 0;
  ForEachCell(window, [&](const CellIndex& c) {
    const int8_t v = values[i++];
    if (packing == CellPacking::kLogOddsInt8) {
      grid.SetLogOdds(c, v * kLogOddsQuantum);
    } else {
      grid.SetState(c, static_cast<CellState>(v));
    }
  });
}

}  // namespace fleetmap::core
