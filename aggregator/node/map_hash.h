// A fingerprint of a map, and the line every run of fleetmap-aggregator ends with, so that
// a live run, a replay of its log and an in-memory run can be compared by one number.
#pragma once

#include <cstdint>
#include <string>

#include "core/map/occupancy_grid.h"

namespace fleetmap::aggregator::node {

// 64-bit FNV-1a over the geometry (resolution, width, height, origin x, y, theta as IEEE
// doubles and int32, little-endian) and every cell's log-odds as IEEE float bits, row-major
// (-0 counted as +0). Equal maps give equal hashes on any machine.
uint64_t MapHash(const core::OccupancyGrid& grid);

// 16 lower-case hex digits.
std::string HashHex(uint64_t hash);

// "aggregator: version N map_hash HEX merged M rejected R": N the current map's version,
// M and R the maps this run merged and rejected.
std::string FinalLine(uint64_t version, uint64_t hash, int64_t merged, int64_t rejected);

}  // namespace fleetmap::aggregator::node
