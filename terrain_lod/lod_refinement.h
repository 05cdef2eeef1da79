// Top-down refinement of the bisection hierarchy for one viewpoint ("Parallel-based Error
// Metric"; Lindstrom & Pascucci 2001, section 4): per tile, starting from its two root triangles,
// a triangle is bisected when its split vertex is active (ScreenErrorMetric), else it is output.
// With nested errors and balls no dependency needs resolving: the output is conforming.
// The triangles of a tile come out in depth-first order and are joined into one triangle strip.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "terrain_lod/bisection_hierarchy.h"
#include "terrain_lod/screen_error_metric.h"

namespace ra::lod {

// Global vertex numbers (TerrainHierarchy::global_vertex), counter-clockwise seen from +z.
using Triangle = std::array<uint32_t, 3>;

struct TileMesh {
  int tx = 0, ty = 0;
  std::vector<Triangle> triangles;  // depth-first order
  std::vector<uint32_t> strip;      // one GL_TRIANGLE_STRIP drawing exactly `triangles`
  int strip_swaps = 0;              // degenerate triangles inserted to change the open edge
  int strip_joins = 0;              // restarts joined by degenerate triangles
};

struct LodMesh {
  std::vector<TileMesh> tiles;  // tiles_y * tiles_x, row-major
  size_t triangle_count() const;
  size_t strip_index_count() const;
  size_t vertex_count() const;  // distinct vertices used (a seam vertex counted once)
};

LodMesh refine(const TerrainHierarchy& h, const ScreenErrorMetric& metric);

// The full-resolution mesh: every tile refined completely (2 (n - 1)^2 triangles per tile).
LodMesh full_resolution(const TerrainHierarchy& h);

// One strip drawing `triangles` in order: the third vertex is appended when a triangle shares
// the strip's last two vertices (a swap, the degenerate (b, c, b), is inserted first when the
// next triangle needs the other edge); otherwise the strip restarts, joined by degenerates.
// Counter-clockwise triangles stay counter-clockwise in GL's reading of the strip.
std::vector<uint32_t> build_strip(const std::vector<Triangle>& triangles, int* swaps, int* joins);

// GL's reading of a strip: triangle k is (s[k], s[k+1], s[k+2]), odd k reversed to
// (s[k+1], s[k], s[k+2]); degenerate ones (a repeated vertex) are left out.
// Used by tests as an independent check of the strips (GL's own reading of them).
std::vector<Triangle> decode_strip(const std::vector<uint32_t>& strip);

}  // namespace ra::lod
