// How the cells of a window are laid out as bytes before compression. Measured in
// bench/codec_bench.cc: 2-bit tri-state packing compresses the LivingLab keyframe best, so
// it is the default for the current map; temporary maps keep their evidence as int8 log-odds
// because the merge needs to know how strongly a cell was observed free.
#pragma once

#include <cstdint>
#include <vector>

#include "core/map/occupancy_grid.h"

namespace fleetmap::core {

enum class CellPacking : uint8_t {
  kTriState2Bit = 0,  // four cells per byte, 0 unknown / 1 free / 2 occupied (3 is invalid)
  kTriState8Bit = 1,  // one byte per cell, same codes
  kLogOddsInt8 = 2,   // one signed byte per cell: log-odds / kLogOddsQuantum, rounded
};

// Quantum of kLogOddsInt8: +-127 quanta cover log-odds +-6.35 (p from 0.002 to 0.998).
constexpr float kLogOddsQuantum = 0.05f;

bool IsValidCellPacking(uint8_t code);
const char* CellPackingName(CellPacking packing);
// Bytes that `num_cells` cells take in `packing`.
int64_t PackedSize(CellPacking packing, int64_t num_cells);

// Cell values in packing terms: CellState codes for the tri-state packings, quanta for int8.
using PackedValues = std::vector<int8_t>;

// Packs the cells of `window` (inside the grid) row by row, bottom row first.
std::vector<uint8_t> PackCells(const OccupancyGrid& grid, const CellWindow& window,
                               CellPacking packing, const OccupancyThresholds& thresholds = {});

// Unpacks `num_cells` values, rejecting codes that no encoder writes (DataLoss).
Result<PackedValues> UnpackCells(const uint8_t* packed, int64_t packed_size, CellPacking packing,
                                 int64_t num_cells);

// Writes unpacked values into `window` of `grid`: tri-state codes become the grid's canonical
// log-odds, quanta become log-odds (clamped to the grid's limits).
void WriteCells(const PackedValues& values, CellPacking packing, const CellWindow& window,
                OccupancyGrid& grid);

}  // namespace fleetmap::core
