#include "scenes/procedural_texture.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "scenes/scene_rng.h"

namespace ra::scenes {
namespace {

struct Rgb {
  double r, g, b;
};

uint8_t to_byte(double v) { return static_cast<uint8_t>(std::clamp(v, 0.0, 1.0) * 255.0 + 0.5); }

}  // namespace

Texture make_texture(TexturePattern pattern, uint64_t seed, int index, int size) {
  if (size < 1 || size > 4096)
    throw std::invalid_argument("texture size " + std::to_string(size) + " is out of range (allowed: 1 to 4096)");
  SceneRng rng(seed, ScenePurpose::kTexture,
               static_cast<uint64_t>(index) * 16 + static_cast<uint64_t>(pattern));
  // a base colour per texture, so that every texture is visibly (and byte-wise) distinct
  Rgb base{};
  switch (pattern) {
    case TexturePattern::kFacade: base = {rng.uniform(0.4, 0.9), rng.uniform(0.3, 0.8), rng.uniform(0.25, 0.7)}; break;
    case TexturePattern::kRoof: base = {0.35, 0.33, 0.32}; break;
    case TexturePattern::kGround: base = {0.25, 0.25, 0.27}; break;
    case TexturePattern::kBark: base = {0.36, 0.24, 0.14}; break;
    case TexturePattern::kLeaves: base = {0.15, rng.uniform(0.35, 0.55), 0.12}; break;
    case TexturePattern::kRock: base = {0.35, 0.45, 0.25}; break;
  }
  Texture t;
  t.width = t.height = size;
  t.rgba.resize(static_cast<size_t>(size) * size * 4);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const double noise = static_cast<double>(rng.next_u64() >> 40) * 0x1.0p-24 - 0.5;  // [-0.5, 0.5)
      const double fx = (x + 0.5) / size, fy = (y + 0.5) / size;
      Rgb c = base;
      double k = 1.0 + 0.15 * noise;
      switch (pattern) {
        case TexturePattern::kFacade: {
          // one window per texture: the facade's texture coordinates repeat once per bay and floor
          const bool window = fx > 0.25 && fx < 0.75 && fy > 0.3 && fy < 0.8;
          if (window) c = {0.2, 0.25, 0.35};
          break;
        }
        case TexturePattern::kBark: k = 0.8 + 0.4 * (0.5 + 0.5 * ((x * 7 / std::max(1, size)) % 2)) + 0.1 * noise; break;
        case TexturePattern::kRock: k = 1.0 + 0.6 * noise; c = fy > 0.5 ? Rgb{0.45, 0.43, 0.4} : base; break;
        default: k = 1.0 + 0.5 * noise; break;
      }
      uint8_t* p = &t.rgba[(static_cast<size_t>(y) * size + x) * 4];
      p[0] = to_byte(c.r * k);
      p[1] = to_byte(c.g * k);
      p[2] = to_byte(c.b * k);
      p[3] = 255;
    }
  return t;
}

}  // namespace ra::scenes
