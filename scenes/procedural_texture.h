// Small seeded RGBA8 textures for the scenes: the study needs distinct textures to switch between
// (state changes, texture memory), not realism. Sizes in texels.
#pragma once

#include <cstdint>

#include "scenes/scene.h"

namespace ra::scenes {

enum class TexturePattern {
  kFacade,  // window grid over a wall colour
  kRoof,    // fine noise over a grey
  kGround,  // asphalt / soil noise
  kBark,    // vertical stripes, brown
  kLeaves,  // green noise
  kRock,    // terrain: grass to rock noise
};

// A size x size texture (size 1..4096) whose colours derive from (seed, index); rows bottom-up.
Texture make_texture(TexturePattern pattern, uint64_t seed, int index, int size);

}  // namespace ra::scenes
