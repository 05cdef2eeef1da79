// Building blocks of the generators: appending vertices and grid-shaped strips to a StripMesh.
// Units: whatever the caller's positions are (metres, world coordinates, +Z up in this project).
#pragma once

#include <cstdint>

#include "geometry/vector_math.h"
#include "scenes/scene.h"

namespace ra::scenes {

// Appends a vertex; returns its number.
uint32_t add_vertex(StripMesh& mesh, geometry::Vec3 p, double s, double t);

// Appends (cols + 1) x (rows + 1) vertices p(u, v) = origin + u / cols * du + v / rows * dv
// (u = 0..cols fastest, v = 0..rows), texture coordinates (s0 + u * s_step, t0 + v * t_step), and
// one strip per row band v..v+1 ordered (v+1, 0), (v, 0), (v+1, 1), (v, 1), ...: 2 * cols
// triangles each, counter-clockwise seen from the side du x dv points to. Consecutive bands share
// a vertex row, which a FIFO cache of >= 2 * (cols + 1) + 2 entries turns into hits.
// Returns the first vertex number.
uint32_t add_grid(StripMesh& mesh, geometry::Vec3 origin, geometry::Vec3 du, geometry::Vec3 dv,
                  int cols, int rows, int texture, double s0, double s_step, double t0,
                  double t_step);

// One strip over the vertices ring[0..n-1] of a convex polygon (in order around it), zig-zagging
// ring[0], ring[1], ring[n-1], ring[2], ring[n-2], ...: n - 2 triangles, none degenerate;
// counter-clockwise when the ring is; `reverse` walks the ring the other way (ring[0],
// ring[n-1], ring[1], ...), flipping which side is front.
void add_polygon_strip(StripMesh& mesh, const uint32_t* ring, int n, int texture, bool reverse);

}  // namespace ra::scenes
