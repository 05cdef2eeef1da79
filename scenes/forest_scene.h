// The forest of the rendering-time study (Wimmer & Wonka 2003, section 7.1, Table 5): trees of
// varying complexity (default 157), each one object: a trunk (open cylinder, one strip per ring
// band, bark texture) and a crown (a sphere or a cone, one strip per band plus zig-zag cap strips,
// leaf texture); and a ground plane. Two textures: 0 bark and ground, 1 leaves.
// Units: metres, world coordinates, +Z up; trees stand on z = 0 within [0, area]^2.
#pragma once

#include <cstdint>
#include <vector>

#include "scenes/scene.h"

namespace ra::scenes {

struct ForestParams {
  uint64_t seed = 1;
  int trees = 157;           // 1..100000
  double area = 250;         // metres, side of the square the trees stand in, > 0
  int slices_min = 6;        // tessellation around the crown, 3..slices_max; the trunk gets
  int slices_max = 96;       //   max(3, slices / 2); 3..1024. Triangles grow as slices^2.
  double height_min = 6;     // metres, tree height, > 0
  double height_max = 25;    // metres, >= height_min
  int texture_size = 128;    // texels per side of each texture, 1..4096
};

enum class CrownShape { kSphere, kCone };

struct TreePlan {
  double x = 0, y = 0;           // metres, foot of the trunk
  double height = 0;             // metres, top of the crown
  double trunk_radius = 0;       // metres
  double trunk_height = 0;       // metres, where the crown's bottom is
  double crown_radius = 0;       // metres
  CrownShape shape = CrownShape::kSphere;
  int slices = 3;                // crown segments around (trunk: max(3, slices / 2))
  int stacks = 2;                // crown bands from bottom to top, >= 2
};

// The layout behind generate_forest (the same draws), for tests.
std::vector<TreePlan> plan_forest(const ForestParams& params);

// Triangles of one tree as generate_forest draws it:
//   trunk: 2 bands of 2 * trunk_slices triangles (trunk_slices = max(3, slices / 2)),
//   crown: stacks bands of 2 * slices, and a bottom and a top cap of slices - 2 each (a zig-zag
//   strip over the end ring, so no degenerate triangles; a cone ends in a ring of 5 % of its
//   base radius, a sphere at +-80 degrees of latitude).
// Used by tests as an analytic check of generate_forest's triangle count.
int64_t tree_triangles(const TreePlan& tree);

// Triangles of the ground object: a 16 x 16 grid of cells, one strip per row: 512.
constexpr int kForestGroundCells = 16;
// Used by tests as an analytic check of generate_forest's triangle count.
int64_t forest_ground_triangles();

// The forest: objects[0] is the ground ("ground"), then one object per tree ("tree K").
// Throws std::invalid_argument when a parameter is outside its range.
Scene generate_forest(const ForestParams& params);

// Throws std::invalid_argument naming the first parameter outside its range.
void validate(const ForestParams& params);

}  // namespace ra::scenes
