// The height field of the terrain level-of-detail study: a regular grid of elevations,
// generated (the seeded fractal of scenes/terrain_scene.h) or read from an elevation image.
// Units: metres; x east, y north, z up; vertex (i, j) lies at (i * spacing, j * spacing, z(i, j)).
#pragma once

#include <string>
#include <vector>

#include "scenes/terrain_scene.h"

namespace ra::lod {

struct HeightField {
  int nx = 0, ny = 0;    // vertices along x and y
  double spacing = 1;    // metres between neighbouring vertices
  std::vector<double> z;  // nx * ny heights, metres, row-major with x fastest
  std::string source;     // "generated seed=..", or the file name (and any cropping done)

  double at(int i, int j) const { return z[static_cast<size_t>(j) * nx + i]; }
};

// Samples terrain_height(params, ...) at nx x ny vertices spaced params.spacing apart
// (params.size is ignored). Throws std::invalid_argument for parameters out of range.
HeightField generate_height_field(const scenes::TerrainParams& params, int nx, int ny);

// Reads a single-channel elevation image (e.g. a GeoTIFF, 16-bit PNG or float TIFF) through
// OpenImageIO: height = value * height_scale metres, where value is the stored number for float
// images and the normalised [0, 1] value for integer ones. Row 0 of the file is the northern edge
// (image order), so file row r becomes j = ny - 1 - r. Throws UserError naming the file for an
// unreadable file, more than one channel, or a NaN / infinite value ("FILE: pixel (x, y) is nan").
HeightField read_height_file(const std::string& path, double spacing, double height_scale);

// Crops `field` (from its south-west corner) to tiles_x * (tile_size - 1) + 1 by
// tiles_y * (tile_size - 1) + 1 vertices, the largest tile counts that fit, at most max_tiles
// per side (0: no limit); appends what it did to `source`. Throws UserError when not even one
// tile fits ("FILE is 100 x 80 vertices: a tile needs 257 x 257").
HeightField crop_to_tiles(const HeightField& field, int tile_size, int max_tiles_x, int max_tiles_y);

}  // namespace ra::lod
