// The terrain of the rendering-time study (Wimmer & Wonka 2003, section 7.1, Table 5): one large
// object, a seeded fractal height field of size x size vertices drawn as one triangle strip per
// row of cells, with one texture.
// Units: metres, world coordinates, +Z up; the grid covers [0, (size - 1) * spacing]^2 in x, y.
#pragma once

#include <cstdint>

#include "scenes/scene.h"

namespace ra::scenes {

struct TerrainParams {
  uint64_t seed = 1;
  int size = 257;             // vertices per side, 2..4097 (triangles: 2 * (size - 1)^2)
  double spacing = 10;        // metres between neighbouring vertices, > 0
  double height_scale = 300;  // metres: heights lie in [0, height_scale]
  double feature_size = 800;  // metres: wavelength of the coarsest noise octave, > 0
  int octaves = 6;            // 1..16, each half the wavelength and `persistence` the amplitude
  double persistence = 0.5;   // 0..1
  int texture_size = 256;     // texels per side of the one texture, 1..4096
};

// The height field behind the terrain, defined everywhere (not just at the vertices): summed
// octaves of value noise (seeded lattice values, smoothstep-interpolated), scaled into
// [0, height_scale]. Continuous in x and y; x, y in metres (any value, also off the grid).
// The later LOD work samples it at other resolutions.
double terrain_height(const TerrainParams& params, double x, double y);

// The terrain: one object "terrain" whose vertex (i, j) (i along x, j along y) is number
// j * size + i at (i * spacing, j * spacing, terrain_height(...)), strips j = 0..size - 2 each
// covering the cells between vertex rows j and j + 1 (2 * size indices). Texture 0, with
// texture coordinates repeating every 16 cells. Fills Scene::layout's ground grid.
// Throws std::invalid_argument when a parameter is outside its range.
Scene generate_terrain(const TerrainParams& params);

// Throws std::invalid_argument naming the first parameter outside its range.
void validate(const TerrainParams& params);

}  // namespace ra::scenes
