// The terrain test scene (Wimmer & Wonka 2003, section 7.1, Figure 9, Table 5): one object.
#include "scenes/terrain_scene.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "scenes/procedural_texture.h"
#include "scenes/scene_rng.h"
#include "scenes/strip_builder.h"

namespace ra::scenes {
namespace {

[[noreturn]] void out_of_range(const char* key, const std::string& value, const std::string& allowed) {
  throw std::invalid_argument(std::string("terrain ") + key + " = " + value +
                              " is out of range (allowed: " + allowed + ")");
}

// The seeded value of lattice point (i, j) of octave o, uniform on [0, 1).
double lattice(uint64_t seed, int o, int64_t i, int64_t j) {
  const uint64_t key =
      util::splitmix64(util::splitmix64(static_cast<uint64_t>(o)) ^ static_cast<uint64_t>(i)) ^
      (static_cast<uint64_t>(j) * 0x9E3779B97F4A7C15ull);
  return SceneRng(seed, ScenePurpose::kTerrainNoise, key).uniform01();
}

double smoothstep(double f) { return f * f * (3 - 2 * f); }

}  // namespace

void validate(const TerrainParams& p) {
  if (p.size < 2 || p.size > 4097) out_of_range("size", std::to_string(p.size), "2 to 4097");
  if (!(p.spacing > 0 && p.spacing <= 1e5)) out_of_range("spacing", std::to_string(p.spacing), "> 0 to 100000");
  if (!(p.height_scale >= 0 && p.height_scale <= 1e5))
    out_of_range("height_scale", std::to_string(p.height_scale), "0 to 100000");
  if (!(p.feature_size > 0 && p.feature_size <= 1e7))
    out_of_range("feature_size", std::to_string(p.feature_size), "> 0 to 10000000");
  if (p.octaves < 1 || p.octaves > 16) out_of_range("octaves", std::to_string(p.octaves), "1 to 16");
  if (!(p.persistence >= 0 && p.persistence <= 1))
    out_of_range("persistence", std::to_string(p.persistence), "0 to 1");
  if (p.texture_size < 1 || p.texture_size > 4096)
    out_of_range("texture_size", std::to_string(p.texture_size), "1 to 4096");
}

double terrain_height(const TerrainParams& p, double x, double y) {
  double sum = 0, amplitude = 1, total = 0, wavelength = p.feature_size;
  for (int o = 0; o < p.octaves; ++o) {
    const double u = x / wavelength, v = y / wavelength;
    const double fu = std::floor(u), fv = std::floor(v);
    const auto i = static_cast<int64_t>(fu), j = static_cast<int64_t>(fv);
    const double su = smoothstep(u - fu), sv = smoothstep(v - fv);
    const double a = lattice(p.seed, o, i, j), b = lattice(p.seed, o, i + 1, j);
    const double c = lattice(p.seed, o, i, j + 1), d = lattice(p.seed, o, i + 1, j + 1);
    const double bottom = a + (b - a) * su, top = c + (d - c) * su;
    sum += amplitude * (bottom + (top - bottom) * sv);
    total += amplitude;
    amplitude *= p.persistence;
    wavelength *= 0.5;
  }
  // each octave lies in [0, 1), so sum / total does: heights in [0, height_scale)
  return p.height_scale * sum / total;
}

Scene generate_terrain(const TerrainParams& p) {
  validate(p);
  Scene scene;
  scene.kind = "terrain";
  SceneLayout& l = scene.layout;
  l.ground_nx = l.ground_ny = p.size;
  l.ground_spacing = p.spacing;
  l.ground_z.reserve(static_cast<size_t>(p.size) * p.size);

  SceneObject o;
  o.name = "terrain";
  StripMesh& m = o.mesh;
  m.positions.reserve(static_cast<size_t>(p.size) * p.size * 3);
  m.texcoords.reserve(static_cast<size_t>(p.size) * p.size * 2);
  float zmax = 0;
  for (int j = 0; j < p.size; ++j)
    for (int i = 0; i < p.size; ++i) {
      const double x = i * p.spacing, y = j * p.spacing;
      add_vertex(m, {x, y, terrain_height(p, x, y)}, i / 16.0, j / 16.0);
      const float z = m.positions.back();  // the float the mesh holds, so the layout agrees with it
      l.ground_z.push_back(z);
      zmax = std::max(zmax, z);
    }
  const auto row = static_cast<uint32_t>(p.size);
  for (uint32_t j = 0; j + 1 < row; ++j) {
    TriangleStrip s;
    s.texture = 0;
    s.indices.reserve(2 * row);
    for (uint32_t i = 0; i < row; ++i) {
      s.indices.push_back((j + 1) * row + i);  // upper row first: counter-clockwise seen from +z
      s.indices.push_back(j * row + i);
    }
    m.strips.push_back(std::move(s));
  }
  o.bounds = enclosing_sphere(m);
  scene.objects.push_back(std::move(o));
  scene.textures.push_back(make_texture(TexturePattern::kRock, p.seed, 0, p.texture_size));
  const double extent = (p.size - 1) * p.spacing;
  l.box_min = {0, 0, 0};
  l.box_max = {extent, extent, zmax};
  return scene;
}

}  // namespace ra::scenes
