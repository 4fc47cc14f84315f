// A temporary map on disk: what a vehicle keeps while the aggregator has not acknowledged it,
// so that it survives a restart of the agent. Binary, little-endian, versioned, CRC-checked;
// the cells are one codec frame (int8 log-odds). Written atomically.
#pragma once

#include <string>

#include "core/io/file_io.h"
#include "core/map/temp_map.h"

namespace fleetmap::core {

std::vector<uint8_t> EncodeTempMap(const TempMap& map);
Result<TempMap> DecodeTempMap(const uint8_t* data, size_t size);

Status SaveTempMap(const TempMap& map, const std::string& path,
                   Durability durability = Durability::kPowerLoss);
Result<TempMap> LoadTempMap(const std::string& path);

}  // namespace fleetmap::core
