// The forest test scene (Wimmer & Wonka 2003, section 7.1, Figure 10, Table 5): 157 trees of
// varying complexity in the paper, two textures.
#include "scenes/forest_scene.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "scenes/procedural_texture.h"
#include "scenes/scene_rng.h"
#include "scenes/strip_builder.h"

namespace ra::scenes {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kBark = 0, kLeaves = 1;

[[noreturn]] void out_of_range(const char* key, const std::string& value, const std::string& allowed) {
  throw std::invalid_argument(std::string("forest ") + key + " = " + value +
                              " is out of range (allowed: " + allowed + ")");
}

int trunk_slices(const TreePlan& t) { return std::max(3, t.slices / 2); }

struct Ring {
  double r, z;  // metres: radius about the tree's axis, height
};

// A surface of revolution about the vertical axis through (x, y): rings bottom to top, each of
// slices + 1 vertices (the seam twice, for texture coordinates), one strip per band, outward
// facing; with `caps`, zig-zag strips close the bottom (facing down) and top (facing up) rings.
void add_revolution(StripMesh& mesh, double x, double y, const std::vector<Ring>& rings, int slices,
                    int texture, bool caps) {
  const uint32_t first = static_cast<uint32_t>(mesh.vertex_count());
  const uint32_t row = static_cast<uint32_t>(slices) + 1;
  for (size_t k = 0; k < rings.size(); ++k)
    for (int u = 0; u <= slices; ++u) {
      const double a = 2 * kPi * (u == slices ? 0 : u) / slices;  // the seam lands exactly
      add_vertex(mesh, {x + rings[k].r * std::cos(a), y + rings[k].r * std::sin(a), rings[k].z},
                 2.0 * u / slices, rings[k].z / 4);
    }
  for (uint32_t k = 0; k + 1 < rings.size(); ++k) {
    TriangleStrip s;
    s.texture = texture;
    s.indices.reserve(2 * row);
    for (uint32_t u = 0; u < row; ++u) {
      s.indices.push_back(first + (k + 1) * row + u);  // upper ring first: outward, counter-clockwise
      s.indices.push_back(first + k * row + u);
    }
    mesh.strips.push_back(std::move(s));
  }
  if (caps) {
    std::vector<uint32_t> ring(static_cast<size_t>(slices));
    for (int u = 0; u < slices; ++u) ring[u] = first + u;
    add_polygon_strip(mesh, ring.data(), slices, texture, /*reverse=*/true);  // seen from below
    const uint32_t top = first + static_cast<uint32_t>(rings.size() - 1) * row;
    for (int u = 0; u < slices; ++u) ring[u] = top + u;
    add_polygon_strip(mesh, ring.data(), slices, texture, /*reverse=*/false);
  }
}

TreePlan plan_tree(const ForestParams& p, int k) {
  SceneRng rng(p.seed, ScenePurpose::kForestTree, static_cast<uint64_t>(k));
  TreePlan t;
  t.x = rng.uniform(0, p.area);
  t.y = rng.uniform(0, p.area);
  t.height = rng.uniform(p.height_min, p.height_max);
  t.trunk_radius = t.height * rng.uniform(0.02, 0.04);
  t.trunk_height = t.height * rng.uniform(0.3, 0.5);
  t.crown_radius = t.height * rng.uniform(0.15, 0.3);
  t.shape = rng.uniform01() < 0.4 ? CrownShape::kCone : CrownShape::kSphere;
  // log-uniform tessellation: as many simple trees as detailed ones, triangles ~ slices^2
  const double ls = rng.uniform(std::log(p.slices_min), std::log(p.slices_max + 1.0));
  t.slices = std::clamp(static_cast<int>(std::floor(std::exp(ls))), p.slices_min, p.slices_max);
  t.stacks = std::max(2, t.slices / 2);
  return t;
}

void add_tree(StripMesh& mesh, const TreePlan& t) {
  // trunk: into the crown by 10 % of the tree, open at both ends (the ground and crown hide them)
  const double trunk_top = t.trunk_height + 0.1 * t.height;
  add_revolution(mesh, t.x, t.y,
                 {{t.trunk_radius, 0}, {t.trunk_radius * 0.9, trunk_top / 2}, {t.trunk_radius * 0.7, trunk_top}},
                 trunk_slices(t), kBark, /*caps=*/false);
  std::vector<Ring> rings;
  const double crown_h = t.height - t.trunk_height;
  for (int k = 0; k <= t.stacks; ++k) {
    const double f = static_cast<double>(k) / t.stacks;
    if (t.shape == CrownShape::kSphere) {
      // an ellipsoid from -80 to +80 degrees of latitude, filling trunk_height..height
      const double lat = (-80 + 160 * f) * kPi / 180;
      const double zc = t.trunk_height + crown_h / 2, half = crown_h / 2 / std::sin(80 * kPi / 180);
      rings.push_back({t.crown_radius * std::cos(lat), zc + half * std::sin(lat)});
    } else {
      rings.push_back({t.crown_radius * (1 - 0.95 * f), t.trunk_height + crown_h * f});
    }
  }
  add_revolution(mesh, t.x, t.y, rings, t.slices, kLeaves, /*caps=*/true);
}

}  // namespace

void validate(const ForestParams& p) {
  if (p.trees < 1 || p.trees > 100000) out_of_range("trees", std::to_string(p.trees), "1 to 100000");
  if (!(p.area > 0 && p.area <= 1e6)) out_of_range("area", std::to_string(p.area), "> 0 to 1000000");
  if (p.slices_max < 3 || p.slices_max > 1024)
    out_of_range("slices_max", std::to_string(p.slices_max), "3 to 1024");
  if (p.slices_min < 3 || p.slices_min > p.slices_max)
    out_of_range("slices_min", std::to_string(p.slices_min), "3 to slices_max = " + std::to_string(p.slices_max));
  if (!(p.height_min > 0 && p.height_min <= 1000))
    out_of_range("height_min", std::to_string(p.height_min), "> 0 to 1000");
  if (!(p.height_max >= p.height_min && p.height_max <= 1000))
    out_of_range("height_max", std::to_string(p.height_max), "height_min to 1000");
  if (p.texture_size < 1 || p.texture_size > 4096)
    out_of_range("texture_size", std::to_string(p.texture_size), "1 to 4096");
}

std::vector<TreePlan> plan_forest(const ForestParams& p) {
  validate(p);
  std::vector<TreePlan> out;
  out.reserve(p.trees);
  for (int k = 0; k < p.trees; ++k) out.push_back(plan_tree(p, k));
  return out;
}

int64_t tree_triangles(const TreePlan& t) {
  return 2LL * 2 * trunk_slices(t) + 2LL * t.stacks * t.slices + 2LL * (t.slices - 2);
}

int64_t forest_ground_triangles() { return 2LL * kForestGroundCells * kForestGroundCells; }

Scene generate_forest(const ForestParams& p) {
  const std::vector<TreePlan> plan = plan_forest(p);  // validates
  Scene scene;
  scene.kind = "forest";
  SceneObject ground;
  ground.name = "ground";
  add_grid(ground.mesh, {0, 0, 0}, {p.area, 0, 0}, {0, p.area, 0}, kForestGroundCells,
           kForestGroundCells, kBark, 0, p.area / kForestGroundCells / 5, 0,
           p.area / kForestGroundCells / 5);
  ground.bounds = enclosing_sphere(ground.mesh);
  scene.objects.push_back(std::move(ground));
  geometry::Vec3 lo{0, 0, 0}, hi{p.area, p.area, 0};
  for (size_t k = 0; k < plan.size(); ++k) {
    SceneObject o;
    o.name = "tree " + std::to_string(k);
    add_tree(o.mesh, plan[k]);
    o.bounds = enclosing_sphere(o.mesh);
    for (size_t i = 0; i < o.mesh.vertex_count(); ++i) {
      const geometry::Vec3 v = o.mesh.vertex(i);
      lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
      hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
    }
    scene.objects.push_back(std::move(o));
  }
  scene.textures.push_back(make_texture(TexturePattern::kBark, p.seed, kBark, p.texture_size));
  scene.textures.push_back(make_texture(TexturePattern::kLeaves, p.seed, kLeaves, p.texture_size));
  scene.layout.box_min = lo;
  scene.layout.box_max = hi;
  return scene;
}

}  // namespace ra::scenes
