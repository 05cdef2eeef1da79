// Seeded random numbers for the scene generators: a pure function of (seed, purpose, item, draw)
// built on SplitMix64 (runner/counter_rng.h), integer arithmetic only, so a seed gives the same
// scene on every machine and standard library (std::uniform_*_distribution would not).
#pragma once

#include <cstdint>

#include "runner/counter_rng.h"

namespace ra {

// Purposes keep the draws of different parts of a generator independent: adding a draw to the
// buildings does not shift the trees.
enum class ScenePurpose : uint64_t {
  kCityBuilding = 0x5101,
  kTerrainNoise = 0x5201,
  kForestTree = 0x5301,
  kCameraWaypoint = 0x5401,
  kTexture = 0x5501,
};

class SceneRng {
 public:
  SceneRng(uint64_t seed, ScenePurpose purpose, uint64_t item)
      : key_(splitmix64(splitmix64(splitmix64(seed) ^ static_cast<uint64_t>(purpose)) ^ item)) {}

  uint64_t next_u64() { return splitmix64(key_ + 0x632BE59BD9B4E019ull * ++counter_); }
  // Uniform on [0, 1) with 53 random bits.
  double uniform01() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }
  // Uniform on [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform01(); }
  // Uniform integer on [lo, hi] (inclusive; hi >= lo). The modulo bias is below 2^-32 for the
  // ranges used here (< 2^32 values).
  int64_t integer(int64_t lo, int64_t hi) {
    const uint64_t span = static_cast<uint64_t>(hi - lo) + 1;
    return lo + static_cast<int64_t>(next_u64() % span);
  }

 private:
  uint64_t key_;
  uint64_t counter_ = 0;
};

}  // namespace ra
