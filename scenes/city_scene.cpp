// The city test scene (Wimmer & Wonka 2003, section 7.1, Figure 8, Table 5).
#include "scenes/city_scene.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "scenes/procedural_texture.h"
#include "scenes/scene_rng.h"
#include "scenes/strip_builder.h"

namespace ra::scenes {
namespace {

void check_int(const char* key, int v, int lo, int hi) {
  if (v < lo || v > hi)
    throw std::invalid_argument(std::string("city ") + key + " = " + std::to_string(v) +
                                " is out of range (allowed: " + std::to_string(lo) + " to " +
                                std::to_string(hi) + ")");
}

void check_real(const char* key, double v, double lo, double hi) {
  if (!(v >= lo && v <= hi))
    throw std::invalid_argument(std::string("city ") + key + " = " + std::to_string(v) +
                                " is out of range (allowed: " + std::to_string(lo) + " to " +
                                std::to_string(hi) + ")");
}

double pitch_of(const CityParams& p) { return p.block_size + p.street_width; }

// The lots of a block: a cols x rows grid with at least `n` cells, filled in row order.
void lot_grid(int n, int& cols, int& rows) {
  cols = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n)) - 1e-9));
  rows = (n + cols - 1) / cols;
}

CityBuilding plan_building(const CityParams& p, int bx, int by, int lot) {
  const uint64_t index =
      (static_cast<uint64_t>(by) * p.blocks_x + bx) * static_cast<uint64_t>(p.buildings_per_block) + lot;
  SceneRng rng(p.seed, ScenePurpose::kCityBuilding, index);
  int cols = 1, rows = 1;
  lot_grid(p.buildings_per_block, cols, rows);
  const double lot_w = p.block_size / cols, lot_d = p.block_size / rows;
  const double lot_x = p.street_width + bx * pitch_of(p) + (lot % cols) * lot_w;
  const double lot_y = p.street_width + by * pitch_of(p) + (lot / cols) * lot_d;

  CityBuilding b;
  b.block_x = bx;
  b.block_y = by;
  b.lot = lot;
  // footprint: 60-90 % of the lot each way, placed anywhere inside it (a 5 % margin at least)
  double w = lot_w * rng.uniform(0.6, 0.9), d = lot_d * rng.uniform(0.6, 0.9);
  double x0 = lot_x + 0.05 * lot_w + rng.uniform01() * (0.9 * lot_w - w);
  double y0 = lot_y + 0.05 * lot_d + rng.uniform01() * (0.9 * lot_d - d);
  const int floors = static_cast<int>(rng.integer(p.floors_min, p.floors_max));
  const int tiers = std::min(floors, static_cast<int>(rng.integer(1, p.tiers_max)));
  int facade = static_cast<int>(rng.integer(2, p.textures - 1));
  int floors_left = floors;
  double z = 0;
  for (int t = 0; t < tiers; ++t) {
    const int tiers_left = tiers - t;
    // each tier takes 40-70 % of the storeys left, leaving one for every tier above it
    int f = tiers_left == 1 ? floors_left
                            : static_cast<int>(std::lround(floors_left * rng.uniform(0.4, 0.7)));
    f = std::clamp(f, 1, floors_left - (tiers_left - 1));
    if (t > 0) {
      // set back: shrink to 60-85 % about a point that keeps the tier on the one below
      const double sw = rng.uniform(0.6, 0.85), sd = rng.uniform(0.6, 0.85);
      x0 += rng.uniform01() * (1 - sw) * w;
      y0 += rng.uniform01() * (1 - sd) * d;
      w *= sw;
      d *= sd;
      if (rng.uniform01() < 0.3) facade = static_cast<int>(rng.integer(2, p.textures - 1));
    }
    CityTier tier;
    tier.x0 = x0;
    tier.y0 = y0;
    tier.x1 = x0 + w;
    tier.y1 = y0 + d;
    tier.z0 = z;
    tier.z1 = z + f * p.floor_height;
    tier.floors = f;
    tier.bays_x = std::max(1, static_cast<int>(std::lround(w / p.bay_width)));
    tier.bays_y = std::max(1, static_cast<int>(std::lround(d / p.bay_width)));
    tier.facade_texture = facade;
    tier.roof_texture = 1;
    b.tiers.push_back(tier);
    z = tier.z1;
    floors_left -= f;
  }
  return b;
}

// Four facades (outward, counter-clockwise from outside; one strip per storey) and a roof.
void add_tier(StripMesh& mesh, const CityTier& t) {
  const double w = t.x1 - t.x0, d = t.y1 - t.y0, h = t.z1 - t.z0;
  const geometry::Vec3 up{0, 0, h};
  struct Face {
    geometry::Vec3 origin, du;
    int bays;
  };
  const Face faces[4] = {
      {{t.x0, t.y0, t.z0}, {w, 0, 0}, t.bays_x},   // south, normal -y
      {{t.x1, t.y0, t.z0}, {0, d, 0}, t.bays_y},   // east, +x
      {{t.x1, t.y1, t.z0}, {-w, 0, 0}, t.bays_x},  // north, +y
      {{t.x0, t.y1, t.z0}, {0, -d, 0}, t.bays_y},  // west, -x
  };
  for (const Face& f : faces)
    add_grid(mesh, f.origin, f.du, up, f.bays, t.floors, t.facade_texture, 0, 1, 0, 1);
  add_grid(mesh, {t.x0, t.y0, t.z1}, {w, 0, 0}, {0, d, 0}, 1, 1, t.roof_texture, 0, w / 10, 0,
           d / 10);
}

// Street and block cells as one grid with lines at every kerb.
StripMesh ground_mesh(const CityParams& p) {
  auto lines = [&](int blocks) {
    std::vector<double> v{0.0};
    for (int i = 0; i < blocks; ++i) {
      v.push_back(p.street_width + i * pitch_of(p));
      v.push_back(p.street_width + i * pitch_of(p) + p.block_size);
    }
    v.push_back(blocks * pitch_of(p) + p.street_width);
    return v;
  };
  const std::vector<double> xs = lines(p.blocks_x), ys = lines(p.blocks_y);
  StripMesh mesh;
  for (double y : ys)
    for (double x : xs) add_vertex(mesh, {x, y, 0}, x / 10, y / 10);
  const auto row = static_cast<uint32_t>(xs.size());
  for (uint32_t j = 0; j + 1 < ys.size(); ++j) {
    TriangleStrip s;
    s.texture = 0;
    for (uint32_t i = 0; i < row; ++i) {
      s.indices.push_back((j + 1) * row + i);
      s.indices.push_back(j * row + i);
    }
    mesh.strips.push_back(std::move(s));
  }
  return mesh;
}

}  // namespace

void validate(const CityParams& p) {
  check_int("blocks_x", p.blocks_x, 1, 1000);
  check_int("blocks_y", p.blocks_y, 1, 1000);
  check_int("buildings_per_block", p.buildings_per_block, 1, 64);
  check_int("textures", p.textures, 3, 256);
  check_int("texture_size", p.texture_size, 1, 4096);
  check_real("block_size", p.block_size, 10, 1000);
  check_real("street_width", p.street_width, 2, 200);
  check_int("floors_max", p.floors_max, 1, 500);
  check_int("floors_min", p.floors_min, 1, p.floors_max);
  check_real("floor_height", p.floor_height, 1, 20);
  check_real("bay_width", p.bay_width, 0.5, 100);
  check_int("tiers_max", p.tiers_max, 1, 8);
  if (static_cast<int64_t>(p.blocks_x) * p.blocks_y * p.buildings_per_block > 4000000)
    throw std::invalid_argument("city blocks_x * blocks_y * buildings_per_block = " +
                                std::to_string(static_cast<int64_t>(p.blocks_x) * p.blocks_y *
                                               p.buildings_per_block) +
                                " is out of range (allowed: up to 4000000 buildings)");
}

std::vector<CityBuilding> plan_city(const CityParams& p) {
  validate(p);
  std::vector<CityBuilding> out;
  out.reserve(static_cast<size_t>(p.blocks_x) * p.blocks_y * p.buildings_per_block);
  for (int by = 0; by < p.blocks_y; ++by)
    for (int bx = 0; bx < p.blocks_x; ++bx)
      for (int lot = 0; lot < p.buildings_per_block; ++lot) out.push_back(plan_building(p, bx, by, lot));
  return out;
}

int64_t city_building_triangles(const CityBuilding& b) {
  int64_t n = 0;
  for (const CityTier& t : b.tiers) n += 2LL * t.floors * 2 * (t.bays_x + t.bays_y) + 2;
  return n;
}

int64_t city_ground_triangles(const CityParams& p) {
  return 2LL * (2 * p.blocks_x + 1) * (2 * p.blocks_y + 1);
}

Scene generate_city(const CityParams& p) {
  const std::vector<CityBuilding> plan = plan_city(p);  // validates
  Scene scene;
  scene.kind = "city";
  scene.objects.reserve(plan.size() + 1);
  SceneObject ground;
  ground.name = "ground";
  ground.mesh = ground_mesh(p);
  ground.bounds = enclosing_sphere(ground.mesh);
  scene.objects.push_back(std::move(ground));
  double top = 0;
  for (size_t k = 0; k < plan.size(); ++k) {
    SceneObject o;
    o.name = "building " + std::to_string(k);
    for (const CityTier& t : plan[k].tiers) {
      add_tier(o.mesh, t);
      top = std::max(top, t.z1);
    }
    o.bounds = enclosing_sphere(o.mesh);
    scene.objects.push_back(std::move(o));
  }
  scene.textures.push_back(make_texture(TexturePattern::kGround, p.seed, 0, p.texture_size));
  scene.textures.push_back(make_texture(TexturePattern::kRoof, p.seed, 1, p.texture_size));
  for (int t = 2; t < p.textures; ++t)
    scene.textures.push_back(make_texture(TexturePattern::kFacade, p.seed, t, p.texture_size));

  SceneLayout& l = scene.layout;
  l.box_min = {0, 0, 0};
  l.box_max = {p.blocks_x * pitch_of(p) + p.street_width, p.blocks_y * pitch_of(p) + p.street_width,
               top};
  l.street_x0 = l.street_y0 = p.street_width / 2;
  l.street_pitch = pitch_of(p);
  l.street_width = p.street_width;
  l.streets_x = p.blocks_x + 1;
  l.streets_y = p.blocks_y + 1;
  return scene;
}

}  // namespace ra::scenes
