// The generator's random numbers: the same seed gives the same world on every machine and
// with every standard library (std::uniform_real_distribution and friends are not specified
// bit for bit, so only the engine, which is, is used).
#pragma once

#include <cstdint>
#include <random>

namespace fleetmap::sim::worldgen {

class Rng {
 public:
  explicit Rng(uint64_t seed) : engine_(seed) {}

  // Uniform in [lo, hi).
  double Uniform(double lo, double hi) {
    const double u = static_cast<double>(engine_() >> 11) * 0x1.0p-53;
    return lo + (hi - lo) * u;
  }
  // Uniform in [lo, hi], whole numbers.
  int Int(int lo, int hi) {
    const uint64_t span = static_cast<uint64_t>(int64_t{hi} - lo) + 1;
    return lo + static_cast<int>(engine_() % span);
  }
  bool Chance(double p) { return Uniform(0.0, 1.0) < p; }
  // A fresh engine for one part of the world, so that adding draws to one part does not
  // change the others.
  Rng Fork() { return Rng(engine_()); }

 private:
  std::mt19937_64 engine_;
};

}  // namespace fleetmap::sim::worldgen
