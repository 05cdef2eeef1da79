// Longest-edge bisection of a square tile of (2^k + 1) x (2^k + 1) height samples, its dependency
// graph (DAG), and the nested object-space errors and bounding-sphere radii of Lindstrom &
// Pascucci ("Visualization of large terrains made easy", 2001) as the terrain LOD study uses it.
//
// Reading of the method's formulas, from its definitions:
//  - The tile is first split into two right triangles by its SW-NE diagonal (so a flat tile is two
//    triangles); a triangle t = (apex a; hypotenuse l-r) is bisected at m = midpoint(l, r) into
//    (m; a-l) and (m; r-a). The diamond of m is the one or two triangles with hypotenuse l-r.
//    DAG: m's children are the split vertices of the four (two on a tile edge) triangles its
//    bisection makes; its parents are the apexes of its diamond.
//  - delta_{i,t} = |z_i - z_t(x_i, y_i)|, the vertical distance of vertex i to the unsplit triangle
//    t. The "maximum" error eps_hat_i = max over t in the diamond T_i, over j in D_{i,t} (i and
//    every descendant reached by bisecting t, i.e. every grid point of the closed triangle t) of
//    delta_{j,t}.
//  - Saturated (nested) error (2): eps_i = max(eps_hat_i, max over DAG children j of eps_j).
//  - Nested ball radius: r_i = max over DAG children j of (|p_j - p_i| + r_j); r = 0 for vertices
//    without children. Then B_i contains B_j for every child j, hence every descendant.
//  - Tile seams: a vertex on an edge shared by two tiles gets eps = max of the two tiles' values
//    and r = max of both radii, and the saturation is run again ("edge error should propagate to
//    its parent too") until nothing changes.
// Units: metres; x east, y north, z up. Local vertex (i, j) of a tile is number j * n + i.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "geometry/vector_math.h"
#include "terrain_lod/height_field.h"

namespace ra::lod {

// A right triangle of the bisection: counter-clockwise (seen from +z) in the order left, right,
// apex; the hypotenuse is left-right. Local vertex numbers of the tile.
struct BisectionTriangle {
  int apex = 0, left = 0, right = 0;
};

// The bisection of one tile size (shared by every tile).
class TileTopology {
 public:
  // n = 2^k + 1, 3 <= n <= 4097. Throws std::invalid_argument otherwise.
  explicit TileTopology(int n);

  int size() const { return n_; }
  int vertex_count() const { return n_ * n_; }
  const std::array<BisectionTriangle, 2>& roots() const { return roots_; }
  // Split vertex of t (midpoint of its hypotenuse), or -1 when t is a half grid cell.
  int split_vertex(const BisectionTriangle& t) const;
  static BisectionTriangle child1(const BisectionTriangle& t, int m) { return {m, t.apex, t.left}; }
  static BisectionTriangle child2(const BisectionTriangle& t, int m) { return {m, t.right, t.apex}; }

  // DAG of split vertices (corners have neither parents nor children).
  const std::vector<int>& children(int v) const { return children_[size_t(v)]; }
  const std::vector<int>& parents(int v) const { return parents_[size_t(v)]; }
  int depth(int v) const { return depth_[size_t(v)]; }  // bisection level: centre 1; corners 0
  // Split vertices, deepest (finest) first: a child always comes before its parents.
  // Used by tests as a check of the hierarchy's order.
  const std::vector<int>& fine_to_coarse() const { return order_; }

 private:
  void visit(const BisectionTriangle& t, int depth);
  int n_;
  std::array<BisectionTriangle, 2> roots_;
  std::vector<std::vector<int>> children_, parents_;
  std::vector<int> depth_, order_;
};

enum class ErrorPropagation {
  kNested,    // saturated errors and nested radii along the DAG (the method)
  kUnnested,  // the deliberately broken variant for the checks: eps = the vertex's own incremental
              // error delta_i = max over its diamond of |z_i - z_t(x_i, y_i)|, radius 0, nothing
              // propagated along the DAG
};

struct TileErrors {
  std::vector<double> eps_hat;  // per local vertex, metres (0 for corners)
  std::vector<double> eps;      // the error refinement uses, metres
  std::vector<double> radius;   // nested ball radius, metres
};

// Every tile's heights and errors. Tile (tx, ty) covers global vertices
// [tx (n - 1), (tx + 1)(n - 1)] x [ty (n - 1), (ty + 1)(n - 1)].
class TerrainHierarchy {
 public:
  // field.nx, ny must be tiles * (tile_size - 1) + 1 (crop_to_tiles). `equalise_seams` false is
  // the second deliberately broken variant (seams may crack).
  TerrainHierarchy(const HeightField& field, int tile_size, ErrorPropagation propagation,
                   bool equalise_seams = true);

  const HeightField& field() const { return *field_; }
  const TileTopology& topology() const { return topo_; }
  int tiles_x() const { return tiles_x_; }
  int tiles_y() const { return tiles_y_; }
  const TileErrors& errors(int tx, int ty) const { return errors_[size_t(ty * tiles_x_ + tx)]; }
  // Global vertex number (gj * field.nx + gi) of local vertex v of tile (tx, ty).
  int global_vertex(int tx, int ty, int v) const;
  // World position of a global vertex, metres.
  geometry::Vec3 position(int global) const;
  int seam_passes() const { return seam_passes_; }  // saturation passes until the seams agreed

 private:
  const HeightField* field_;
  TileTopology topo_;
  int tiles_x_, tiles_y_;
  std::vector<TileErrors> errors_;
  int seam_passes_ = 0;
};

// delta_i = max over the diamond of |z_i - z_t(x_i, y_i)| of every local vertex of tile (tx, ty).
std::vector<double> incremental_errors(const TileTopology& topo, const HeightField& field, int tx, int ty);

// eps_hat of every local vertex of tile (tx, ty) straight from the definition (every triangle of
// every level, every grid point in it). Exposed for tests.
std::vector<double> maximum_errors(const TileTopology& topo, const HeightField& field, int tx, int ty);

}  // namespace ra::lod
