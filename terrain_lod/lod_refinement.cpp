// Top-down refinement and strips (lod_refinement.h; Lindstrom & Pascucci 2001, "construct the triangle strip").
#include "terrain_lod/lod_refinement.h"

#include <algorithm>

namespace ra::lod {
namespace {

bool has(const Triangle& t, uint32_t v) { return t[0] == v || t[1] == v || t[2] == v; }

// The vertex of t that is neither a nor b.
uint32_t third(const Triangle& t, uint32_t a, uint32_t b) {
  for (uint32_t v : t)
    if (v != a && v != b) return v;
  return t[0];
}

bool shares_edge(const Triangle* next, uint32_t a, uint32_t b) {
  return next && a != b && has(*next, a) && has(*next, b);
}

// Rotation of t = (x, y, z) whose last two vertices (y, z) are an edge `next` shares, if any.
Triangle rotate_for(const Triangle& t, const Triangle* next) {
  for (int k = 0; k < 3; ++k) {
    const Triangle r = {t[size_t(k)], t[size_t((k + 1) % 3)], t[size_t((k + 2) % 3)]};
    if (shares_edge(next, r[1], r[2])) return r;
  }
  return t;
}

// Depth-first, in the order of a Sierpinski curve, so that consecutive output triangles share
// an edge (what a strip needs): a triangle is walked from its hypotenuse's left end to its right
// end (or back when `reversed`); its children are then walked l -> a -> r (c1 then c2, both
// reversed) or r -> a -> l (c2 then c1, both forward).
template <typename F>
void refine_triangle(const TileTopology& topo, const BisectionTriangle& t, bool reversed, const F& active,
                     std::vector<BisectionTriangle>& out) {
  const int m = topo.split_vertex(t);
  if (m >= 0 && active(m)) {
    if (!reversed) {
      refine_triangle(topo, TileTopology::child1(t, m), true, active, out);
      refine_triangle(topo, TileTopology::child2(t, m), true, active, out);
    } else {
      refine_triangle(topo, TileTopology::child2(t, m), false, active, out);
      refine_triangle(topo, TileTopology::child1(t, m), false, active, out);
    }
  } else {
    out.push_back(t);
  }
}

template <typename F>
LodMesh refine_with(const TerrainHierarchy& h, const F& active_in_tile) {
  LodMesh mesh;
  const TileTopology& topo = h.topology();
  std::vector<BisectionTriangle> local;
  for (int ty = 0; ty < h.tiles_y(); ++ty)
    for (int tx = 0; tx < h.tiles_x(); ++tx) {
      TileMesh tm;
      tm.tx = tx;
      tm.ty = ty;
      local.clear();
      auto active = [&](int v) { return active_in_tile(tx, ty, v); };
      // root 0 runs NE -> SW, root 1 SW -> NE
      for (const BisectionTriangle& r : topo.roots()) refine_triangle(topo, r, false, active, local);
      tm.triangles.reserve(local.size());
      for (const BisectionTriangle& t : local)
        tm.triangles.push_back({uint32_t(h.global_vertex(tx, ty, t.left)), uint32_t(h.global_vertex(tx, ty, t.right)),
                                uint32_t(h.global_vertex(tx, ty, t.apex))});
      tm.strip = build_strip(tm.triangles, &tm.strip_swaps, &tm.strip_joins);
      mesh.tiles.push_back(std::move(tm));
    }
  return mesh;
}

}  // namespace

size_t LodMesh::triangle_count() const {
  size_t n = 0;
  for (const TileMesh& t : tiles) n += t.triangles.size();
  return n;
}

size_t LodMesh::strip_index_count() const {
  size_t n = 0;
  for (const TileMesh& t : tiles) n += t.strip.size();
  return n;
}

size_t LodMesh::vertex_count() const {
  std::vector<uint32_t> v;
  for (const TileMesh& t : tiles)
    for (const Triangle& tri : t.triangles) v.insert(v.end(), tri.begin(), tri.end());
  std::sort(v.begin(), v.end());
  return size_t(std::unique(v.begin(), v.end()) - v.begin());
}

LodMesh refine(const TerrainHierarchy& h, const ScreenErrorMetric& metric) {
  return refine_with(h, [&](int tx, int ty, int v) {
    const TileErrors& e = h.errors(tx, ty);
    return metric.active(e.eps[size_t(v)], e.radius[size_t(v)], h.position(h.global_vertex(tx, ty, v)));
  });
}

LodMesh full_resolution(const TerrainHierarchy& h) {
  return refine_with(h, [](int, int, int) { return true; });
}

std::vector<uint32_t> build_strip(const std::vector<Triangle>& tris, int* swaps, int* joins) {
  std::vector<uint32_t> s;
  s.reserve(tris.size() * 2 + 4);
  int n_swaps = 0, n_joins = 0;
  for (size_t i = 0; i < tris.size(); ++i) {
    const Triangle& t = tris[i];
    const Triangle* next = i + 1 < tris.size() ? &tris[i + 1] : nullptr;
    if (s.size() >= 2) {
      const uint32_t p = s[s.size() - 2], q = s[s.size() - 1];
      const bool even = (s.size() - 2) % 2 == 0;
      if (p != q && has(t, p) && has(t, q)) {
        const uint32_t w = third(t, p, q);
        // GL reads the new triangle as (p, q, w) at an even index, (q, p, w) at an odd one
        const Triangle seen = even ? Triangle{p, q, w} : Triangle{q, p, w};
        const bool same_winding = seen == t || seen == Triangle{t[1], t[2], t[0]} || seen == Triangle{t[2], t[0], t[1]};
        if (same_winding) {
          if (!shares_edge(next, q, w) && shares_edge(next, p, w)) {
            s.push_back(p);  // swap: the degenerate (q, p, p)... keeps the winding, opens (p, w)
            ++n_swaps;
          }
          s.push_back(w);
          continue;
        }
      }
      // restart: degenerates (p, q, q), (q, q, x), (q, x, x), ... up to an even start index
      const Triangle r = rotate_for(t, next);
      s.push_back(q);
      s.push_back(r[0]);
      s.push_back(r[0]);
      if ((s.size() - 1) % 2 != 0) s.push_back(r[0]);
      s.push_back(r[1]);
      s.push_back(r[2]);
      ++n_joins;
      continue;
    }
    const Triangle r = rotate_for(t, next);
    s.insert(s.end(), r.begin(), r.end());
  }
  if (swaps) *swaps = n_swaps;
  if (joins) *joins = n_joins;
  return s;
}

std::vector<Triangle> decode_strip(const std::vector<uint32_t>& s) {
  std::vector<Triangle> out;
  for (size_t k = 0; k + 2 < s.size(); ++k) {
    const uint32_t a = s[k], b = s[k + 1], c = s[k + 2];
    if (a == b || b == c || a == c) continue;
    out.push_back(k % 2 == 0 ? Triangle{a, b, c} : Triangle{b, a, c});
  }
  return out;
}

}  // namespace ra::lod
