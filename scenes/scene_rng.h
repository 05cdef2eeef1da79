// Seeded random numbers for the scene generators: a pure function of (seed, purpose, item, draw)
// built on SplitMix64 (util/counter_rng.h), integer arithmetic only, so a seed gives the same
// scene on every machine and standard library (std::uniform_*_distribution would not).
#pragma once

#include <cstdint>

#include "util/counter_rng.h"

namespace ra::scenes {

// Purposes keep the draws of different parts of a generator independent: adding a draw to the
// buildings does not shift the trees.
enum class ScenePurpose : uint64_t {
  kCityBuilding = 0x5101,
  kTerrainNoise = 0x5201,
  kForestTree = 0x5301,
  kCameraWaypoint = 0x5401,
  kTexture = 0x5501,
};

// The draws of one item of one purpose: runner's counter-based generator under a scene tag.
class SceneRng : public util::CounterRng {
 public:
  SceneRng(uint64_t seed, ScenePurpose purpose, uint64_t item)
      : util::CounterRng(seed, static_cast<uint64_t>(purpose), item) {}
};

}  // namespace ra::scenes
