// The city of the rendering-time study (Wimmer & Wonka 2003, section 7.1, Table 5): thousands of
// buildings, each one object made of indexed triangle strips (facade grids row by row, roofs) with
// several textures, so drawing it switches texture state often; plus one ground object.
// Units: metres, world coordinates, +Z up; ground at z = 0. With pitch = block_size + street_width
// the city covers [0, blocks_x * pitch + street_width] x [0, blocks_y * pitch + street_width]:
// streets all round, street centre lines at x = street_width / 2 + i * pitch (i = 0..blocks_x).
#pragma once

#include <cstdint>
#include <vector>

#include "scenes/scene.h"

namespace ra::scenes {

struct CityParams {
  uint64_t seed = 1;
  int blocks_x = 40;             // city blocks along x, 1..1000
  int blocks_y = 40;             // city blocks along y, 1..1000
  int buildings_per_block = 4;   // 1..64: lots on a ceil(sqrt(n)) x ceil(n / cols) grid per block
  int textures = 8;              // 3..256: 0 ground, 1 roofs, 2.. facades (drawn per building)
  int texture_size = 64;         // texels per side of each texture, 1..4096
  double block_size = 60;        // metres, side of a square block (kerb to kerb), 10..1000
  double street_width = 15;      // metres, 2..200
  int floors_min = 2;            // storeys of a building, 1..floors_max
  int floors_max = 16;           // 1..500
  double floor_height = 3.5;     // metres per storey (one facade strip per storey)
  double bay_width = 5;          // metres: a facade gets round(width / bay_width) >= 1 columns
  int tiers_max = 3;             // 1..8: a building is 1..tiers_max boxes, each set back on the last
};

// One box of a building: a footprint rectangle from z0 to z1, its facades a grid of
// bays_x (faces along x) or bays_y (faces along y) columns by `floors` rows; roof on top.
struct CityTier {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // metres, footprint, x0 < x1, y0 < y1
  double z0 = 0, z1 = 0;                  // metres, bottom and top
  int floors = 1, bays_x = 1, bays_y = 1;
  int facade_texture = 2, roof_texture = 1;
};

struct CityBuilding {
  int block_x = 0, block_y = 0, lot = 0;
  std::vector<CityTier> tiers;  // bottom to top
};

// The layout behind generate_city (the same draws), for tests and for describing a city.
std::vector<CityBuilding> plan_city(const CityParams& params);

// Triangles of one building as generate_city draws it: per tier 2 * floors * 2 * (bays_x +
// bays_y) facade triangles (one strip per storey per face) + 2 roof triangles (one strip).
// Used by tests as an analytic check of generate_city's triangle count.
int64_t city_building_triangles(const CityBuilding& building);

// Triangles of the ground object: one quad per block and per street cell, i.e. a grid of
// (2 * blocks_x + 1) x (2 * blocks_y + 1) cells, one strip per row of cells.
// Used by tests as an analytic check of generate_city's triangle count.
int64_t city_ground_triangles(const CityParams& params);

// The city: objects[0] is the ground ("ground"), then one object per building ("building K"),
// in plan order. Throws std::invalid_argument when a parameter is outside its range.
Scene generate_city(const CityParams& params);

// Throws std::invalid_argument naming the first parameter outside its range.
void validate(const CityParams& params);

}  // namespace ra::scenes
