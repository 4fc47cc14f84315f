// The input format of map_load_fuzz, shared with the seed writer: a map_server YAML and its
// PGM image in one buffer.
//   bytes 0..1  YAML length n, little-endian (cut to what the input holds)
//   then        n bytes of YAML, then the PGM file
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace fleetmap::fuzz {

struct MapYamlPgmInput {
  std::string_view yaml;
  std::string_view pgm;
};

inline MapYamlPgmInput ReadMapYamlPgm(const uint8_t* data, size_t size) {
  if (size < 2) return {};
  const auto* text = reinterpret_cast<const char*>(data) + 2;
  const size_t n = std::min<size_t>(data[0] | size_t{data[1]} << 8, size - 2);
  return {std::string_view(text, n), std::string_view(text + n, size - 2 - n)};
}

inline std::string WriteMapYamlPgm(const std::string& yaml, const std::string& pgm) {
  std::string out = {static_cast<char>(yaml.size() & 0xFF), static_cast<char>(yaml.size() >> 8)};
  return out + yaml + pgm;
}

}  // namespace fleetmap::fuzz
