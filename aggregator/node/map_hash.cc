#include "aggregator/node/map_hash.h"

#include <cinttypes>
#include <cstdio>
#include <cstring>

namespace fleetmap::aggregator::node {
namespace {

class Fnv1a {
 public:
  void Byte(uint8_t b) {
    h_ ^= b;
    h_ *= 0x100000001b3ULL;
  }
  void U32(uint32_t v) {
    for (int i = 0; i < 4; ++i) Byte(static_cast<uint8_t>(v >> (8 * i)));
  }
  void U64(uint64_t v) {
    for (int i = 0; i < 8; ++i) Byte(static_cast<uint8_t>(v >> (8 * i)));
  }
  void Double(double d) {
    uint64_t bits;
    d = d == 0.0 ? 0.0 : d;
    std::memcpy(&bits, &d, sizeof bits);
    U64(bits);
  }
  void Float(float f) {
    uint32_t bits;
    f = f == 0.0f ? 0.0f : f;
    std::memcpy(&bits, &f, sizeof bits);
    U32(bits);
  }
  uint64_t value() const { return h_; }

 private:
  uint64_t h_ = 0xcbf29ce484222325ULL;
};

}  // namespace

uint64_t MapHash(const core::OccupancyGrid& grid) {
  const core::GridGeometry& g = grid.geometry();
  Fnv1a h;
  h.Double(g.resolution_m());
  h.U32(static_cast<uint32_t>(g.width()));
  h.U32(static_cast<uint32_t>(g.height()));
  h.Double(g.origin().x_m);
  h.Double(g.origin().y_m);
  h.Double(g.origin().theta_rad);
  for (float cell : grid.cells()) h.Float(cell);
  return h.value();
}

std::string HashHex(uint64_t hash) {
  char text[17];
  std::snprintf(text, sizeof text, "%016" PRIx64, hash);
  return text;
}

std::string FinalLine(uint64_t version, uint64_t hash, int64_t merged, int64_t rejected) {
  return "aggregator: version " + std::to_string(version) + " map_hash " + HashHex(hash) +
         " merged " + std::to_string(merged) + " rejected " + std::to_string(rejected);
}

}  // namespace fleetmap::aggregator::node
