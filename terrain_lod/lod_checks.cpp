// Conformity and screen-error checks of a LOD mesh (lod_checks.h).
#include "terrain_lod/lod_checks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>

namespace ra::lod {
namespace {

int64_t area2(int64_t ax, int64_t ay, int64_t bx, int64_t by, int64_t cx, int64_t cy) {
  return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

}  // namespace

std::vector<Triangle> all_triangles(const LodMesh& mesh) {
  std::vector<Triangle> out;
  out.reserve(mesh.triangle_count());
  for (const TileMesh& t : mesh.tiles) out.insert(out.end(), t.triangles.begin(), t.triangles.end());
  return out;
}

ConformityResult check_conformity(const std::vector<Triangle>& tris, int nx, int ny) {
  ConformityResult r;
  auto note = [&](const std::string& what) {
    if (r.first_problem.empty()) r.first_problem = what;
  };
  auto gx = [&](uint32_t v) { return int64_t(v % uint32_t(nx)); };
  auto gy = [&](uint32_t v) { return int64_t(v / uint32_t(nx)); };
  auto name = [&](uint32_t v) { return "(" + std::to_string(gx(v)) + ", " + std::to_string(gy(v)) + ")"; };
  std::vector<char> used(size_t(nx) * ny, 0);
  std::vector<uint64_t> edges;  // directed, u << 32 | v, as the counter-clockwise triangles run
  edges.reserve(tris.size() * 3);
  int64_t total = 0;
  for (const Triangle& t : tris) {
    const int64_t a = area2(gx(t[0]), gy(t[0]), gx(t[1]), gy(t[1]), gx(t[2]), gy(t[2]));
    if (a <= 0) {
      ++r.inverted;
      note("triangle " + name(t[0]) + " " + name(t[1]) + " " + name(t[2]) + " is not counter-clockwise");
    }
    total += a;
    for (int k = 0; k < 3; ++k) {
      used[t[size_t(k)]] = 1;
      edges.push_back(uint64_t(t[size_t(k)]) << 32 | t[size_t((k + 1) % 3)]);
    }
  }
  r.area_matches = total == 2 * int64_t(nx - 1) * (ny - 1);
  if (!r.area_matches) note("the triangles' areas do not sum to the terrain's (overlap or hole)");
  std::sort(edges.begin(), edges.end());
  auto on_boundary = [&](uint32_t u, uint32_t v) {
    return (gx(u) == 0 && gx(v) == 0) || (gx(u) == nx - 1 && gx(v) == nx - 1) || (gy(u) == 0 && gy(v) == 0) ||
           (gy(u) == ny - 1 && gy(v) == ny - 1);
  };
  for (size_t i = 0; i < edges.size(); ++i) {
    const auto u = uint32_t(edges[i] >> 32), v = uint32_t(edges[i] & 0xffffffffu);
    if (i + 1 < edges.size() && edges[i + 1] == edges[i]) {
      ++r.overlapping;
      note("edge " + name(u) + "-" + name(v) + " has two triangles on one side");
    }
    if (!on_boundary(u, v) && !std::binary_search(edges.begin(), edges.end(), uint64_t(v) << 32 | u)) {
      ++r.open_edges;
      note("edge " + name(u) + "-" + name(v) + " has a triangle on one side only (crack or T-junction)");
    }
    // lattice points strictly inside the edge: any used one is a T-junction
    const int64_t dx = gx(v) - gx(u), dy = gy(v) - gy(u);
    const int64_t g = std::gcd(std::llabs(dx), std::llabs(dy));
    for (int64_t k = 1; k < g; ++k) {
      const int64_t x = gx(u) + dx / g * k, y = gy(u) + dy / g * k;
      if (used[size_t(y * nx + x)]) {
        ++r.t_junctions;
        note("vertex (" + std::to_string(x) + ", " + std::to_string(y) + ") lies inside edge " + name(u) + "-" +
             name(v) + " (T-junction)");
        break;
      }
    }
  }
  r.conforming = r.inverted == 0 && r.overlapping == 0 && r.open_edges == 0 && r.t_junctions == 0 && r.area_matches;
  return r;
}

SeamResult check_seams(const LodMesh& mesh, const TerrainHierarchy& h) {
  SeamResult r;
  const int n = h.topology().size(), nx = h.field().nx;
  // Per tile, which vertices of its four edges its triangles use: four flag arrays of length n
  // (west, east, south, north; index along the edge), O(tiles * n) memory.
  enum { kWest = 0, kEast = 1, kSouth = 2, kNorth = 3 };
  std::vector<std::array<std::vector<char>, 4>> used(mesh.tiles.size());
  for (size_t k = 0; k < mesh.tiles.size(); ++k) {
    const TileMesh& tile = mesh.tiles[k];
    for (auto& e : used[k]) e.assign(size_t(n), 0);
    const int64_t gi0 = int64_t(tile.tx) * (n - 1), gj0 = int64_t(tile.ty) * (n - 1);
    for (const Triangle& t : tile.triangles)
      for (uint32_t v : t) {
        const int64_t i = int64_t(v % uint32_t(nx)) - gi0, j = int64_t(v / uint32_t(nx)) - gj0;
        if (i < 0 || j < 0 || i >= n || j >= n) continue;  // not this tile's vertex (conformity reports it)
        if (i == 0) used[k][kWest][size_t(j)] = 1;
        if (i == n - 1) used[k][kEast][size_t(j)] = 1;
        if (j == 0) used[k][kSouth][size_t(i)] = 1;
        if (j == n - 1) used[k][kNorth][size_t(i)] = 1;
      }
  }
  auto compare = [&](const std::vector<char>& a, const std::vector<char>& b, int g0, int step,
                     const std::string& which) {
    ++r.seams;
    for (int s = 0; s < n; ++s) {
      if (a[size_t(s)] != b[size_t(s)]) {
        const int64_t g = int64_t(g0) + int64_t(s) * step;
        ++r.mismatched;
        r.ok = false;
        if (r.first_problem.empty())
          r.first_problem = which + ": vertex (" + std::to_string(g % nx) + ", " + std::to_string(g / nx) +
                            ") is used by one tile only (crack)";
      }
    }
  };
  for (int ty = 0; ty < h.tiles_y(); ++ty)
    for (int tx = 0; tx < h.tiles_x(); ++tx) {
      const size_t a = size_t(ty * h.tiles_x() + tx);
      const std::string tile = "tile (" + std::to_string(tx) + ", " + std::to_string(ty) + ")";
      if (tx + 1 < h.tiles_x())
        compare(used[a][kEast], used[a + 1][kWest], h.global_vertex(tx, ty, n - 1), nx, tile + " east seam");
      if (ty + 1 < h.tiles_y())
        compare(used[a][kNorth], used[a + size_t(h.tiles_x())][kSouth], h.global_vertex(tx, ty, (n - 1) * n), 1,
                tile + " north seam");
    }
  return r;
}

std::vector<double> lod_surface_heights(const LodMesh& mesh, const HeightField& f) {
  std::vector<double> z(f.z.size(), std::nan(""));
  const auto nx = uint32_t(f.nx);
  for (const TileMesh& tile : mesh.tiles)
    for (const Triangle& t : tile.triangles) {
      int64_t xi[3], yi[3];
      for (int k = 0; k < 3; ++k) {
        xi[k] = t[size_t(k)] % nx;
        yi[k] = t[size_t(k)] / nx;
      }
      const int64_t a = area2(xi[0], yi[0], xi[1], yi[1], xi[2], yi[2]);
      if (a <= 0) continue;
      const int64_t x0 = std::min({xi[0], xi[1], xi[2]}), x1 = std::max({xi[0], xi[1], xi[2]});
      const int64_t y0 = std::min({yi[0], yi[1], yi[2]}), y1 = std::max({yi[0], yi[1], yi[2]});
      const double z0 = f.z[t[0]], z1 = f.z[t[1]], z2 = f.z[t[2]];
      for (int64_t y = y0; y <= y1; ++y)
        for (int64_t x = x0; x <= x1; ++x) {
          const int64_t w0 = area2(x, y, xi[1], yi[1], xi[2], yi[2]);
          const int64_t w1 = area2(x, y, xi[2], yi[2], xi[0], yi[0]);
          const int64_t w2 = a - w0 - w1;
          if (w0 < 0 || w1 < 0 || w2 < 0) continue;
          z[size_t(y * f.nx + x)] = (double(w0) * z0 + double(w1) * z1 + double(w2) * z2) / double(a);
        }
    }
  return z;
}

ScreenErrorResult measure_screen_error(const std::vector<double>& z_lod, const HeightField& f,
                                       const scenes::CameraSettings& cam,
                                       const scenes::Viewpoint& vp) {
  ScreenErrorResult r;
  const geometry::Mat4 m = scenes::projection_of(cam) * scenes::look_at(vp);
  auto window = [&](const geometry::Vec4& c, double* px, double* py) {
    *px = (c.x / c.w + 1) * 0.5 * cam.width;
    *py = (c.y / c.w + 1) * 0.5 * cam.height;
  };
  for (int j = 0; j < f.ny; ++j)
    for (int i = 0; i < f.nx; ++i) {
      const size_t g = size_t(j) * f.nx + i;
      const double x = i * f.spacing, y = j * f.spacing;
      const geometry::Vec4 a = m * geometry::Vec4{x, y, f.z[g], 1};
      if (!std::isfinite(z_lod[g])) {  // a hole: no LOD triangle covers this vertex
        ++r.holes;
        if (r.holes == 1) {  // the first hole is the worst vertex (infinite error)
          r.max_px = std::numeric_limits<double>::infinity();
          r.worst_vertex = int(g);
          r.worst_x = r.worst_y = std::nan("");
          if (a.w > 0) window(a, &r.worst_x, &r.worst_y);
        }
        continue;
      }
      const geometry::Vec4 b = m * geometry::Vec4{x, y, z_lod[g], 1};
      double t0, t1;
      if (!clip_segment(a, b, &t0, &t1)) {
        ++r.excluded;
        continue;
      }
      ++r.checked;
      if (t0 > 0 || t1 < 1) ++r.partially_visible;
      const geometry::Vec4 ca = a + t0 * (b - a), cb = a + t1 * (b - a);
      double ax, ay, bx, by;
      window(ca, &ax, &ay);
      window(cb, &bx, &by);
      const double d = std::hypot(ax - bx, ay - by);
      if (d > r.max_px) {
        r.max_px = d;
        r.worst_vertex = int(g);
        r.worst_x = ax;
        r.worst_y = ay;
      }
    }
  return r;
}

bool clip_segment(const geometry::Vec4& a, const geometry::Vec4& b, double* t0, double* t1) {
  // Liang-Barsky: the inside of plane k is d_k(c) >= 0 with d_k linear in the clip coordinates,
  // so along c(t) = a + t (b - a) each plane cuts [0, 1] at one t.
  const double da[6] = {a.w + a.x, a.w - a.x, a.w + a.y, a.w - a.y, a.w + a.z, a.w - a.z};
  const double db[6] = {b.w + b.x, b.w - b.x, b.w + b.y, b.w - b.y, b.w + b.z, b.w - b.z};
  double lo = 0, hi = 1;
  for (int k = 0; k < 6; ++k) {
    if (da[k] < 0 && db[k] < 0) return false;  // wholly outside this plane
    if (da[k] < 0) lo = std::max(lo, da[k] / (da[k] - db[k]));       // enters at t
    else if (db[k] < 0) hi = std::min(hi, da[k] / (da[k] - db[k]));  // leaves at t
  }
  if (!(lo <= hi)) return false;
  // inside all six planes w >= |x|, |y|, |z|; w = 0 only at the eye itself (never with near > 0)
  const double wa = a.w + (b.w - a.w) * lo, wb = a.w + (b.w - a.w) * hi;
  if (!(wa > 0) || !(wb > 0)) return false;
  *t0 = lo;
  *t1 = hi;
  return true;
}

}  // namespace ra::lod
