// Longest-edge bisection, its DAG, and nested errors and radii (bisection_hierarchy.h; Lindstrom & Pascucci 2001,
// "Nested Geometric Error And Screen Error", "Geometric Error Metric", "Seamless Connection").
#include "terrain_lod/bisection_hierarchy.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ra::lod {
namespace {

void add_unique(std::vector<int>& list, int v) {
  if (std::find(list.begin(), list.end(), v) == list.end()) list.push_back(v);
}

// Largest |z - z_t| over the grid points of the closed triangle t (local numbers of a tile whose
// south-west vertex is global (gi0, gj0)); z_t is the linear interpolation of t's corners.
double triangle_max_deviation(const BisectionTriangle& t, int n, const HeightField& f, int gi0, int gj0) {
  const int v[3] = {t.left, t.right, t.apex};
  int xi[3], yi[3];
  double zv[3];
  for (int k = 0; k < 3; ++k) {
    xi[k] = v[k] % n;
    yi[k] = v[k] / n;
    zv[k] = f.at(gi0 + xi[k], gj0 + yi[k]);
  }
  const int64_t area2 = int64_t(xi[1] - xi[0]) * (yi[2] - yi[0]) - int64_t(yi[1] - yi[0]) * (xi[2] - xi[0]);
  const int x0 = std::min({xi[0], xi[1], xi[2]}), x1 = std::max({xi[0], xi[1], xi[2]});
  const int y0 = std::min({yi[0], yi[1], yi[2]}), y1 = std::max({yi[0], yi[1], yi[2]});
  double worst = 0;
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      // barycentric weights times area2, exact in integers: inside (closed) when all >= 0
      const int64_t w0 = int64_t(xi[1] - x) * (yi[2] - y) - int64_t(yi[1] - y) * (xi[2] - x);
      const int64_t w1 = int64_t(xi[2] - x) * (yi[0] - y) - int64_t(yi[2] - y) * (xi[0] - x);
      const int64_t w2 = area2 - w0 - w1;
      if (w0 < 0 || w1 < 0 || w2 < 0) continue;
      const double zt = (double(w0) * zv[0] + double(w1) * zv[1] + double(w2) * zv[2]) / double(area2);
      worst = std::max(worst, std::abs(f.at(gi0 + x, gj0 + y) - zt));
    }
  return worst;
}

void max_errors_visit(const TileTopology& topo, const BisectionTriangle& t, const HeightField& f,
                      int gi0, int gj0, std::vector<double>& eps_hat) {
  const int m = topo.split_vertex(t);
  if (m < 0) return;
  double& e = eps_hat[size_t(m)];
  e = std::max(e, triangle_max_deviation(t, topo.size(), f, gi0, gj0));
  max_errors_visit(topo, TileTopology::child1(t, m), f, gi0, gj0, eps_hat);
  max_errors_visit(topo, TileTopology::child2(t, m), f, gi0, gj0, eps_hat);
}

}  // namespace

TileTopology::TileTopology(int n) : n_(n) {
  if (n < 3 || n > 4097 || ((n - 1) & (n - 2)) != 0)
    throw std::invalid_argument("tile size " + std::to_string(n) + " is not 2^k + 1 in 3..4097");
  const int sw = 0, se = n - 1, nw = (n - 1) * n, ne = n * n - 1;
  // the SW-NE diagonal is the first hypotenuse; both halves counter-clockwise (left, right, apex)
  roots_ = {BisectionTriangle{se, ne, sw}, BisectionTriangle{nw, sw, ne}};
  children_.resize(size_t(n) * n);
  parents_.resize(size_t(n) * n);
  depth_.assign(size_t(n) * n, 0);
  for (const BisectionTriangle& t : roots_) visit(t, 1);
  for (int v = 0; v < n * n; ++v)
    if (depth_[size_t(v)] > 0) order_.push_back(v);
  std::stable_sort(order_.begin(), order_.end(), [&](int a, int b) { return depth_[size_t(a)] > depth_[size_t(b)]; });
}

int TileTopology::split_vertex(const BisectionTriangle& t) const {
  const int sx = t.left % n_ + t.right % n_, sy = t.left / n_ + t.right / n_;
  if ((sx & 1) || (sy & 1)) return -1;  // the hypotenuse is a cell diagonal: no grid point inside
  return (sy / 2) * n_ + sx / 2;
}

void TileTopology::visit(const BisectionTriangle& t, int depth) {
  const int m = split_vertex(t);
  if (m < 0) return;
  if (depth_[size_t(m)] != 0 && depth_[size_t(m)] != depth)
    throw std::logic_error("bisection: a vertex at two depths");  // both diamond halves share a level
  depth_[size_t(m)] = depth;
  if (depth > 1) add_unique(parents_[size_t(m)], t.apex);
  const BisectionTriangle c[2] = {child1(t, m), child2(t, m)};
  for (const BisectionTriangle& ct : c) {
    const int cm = split_vertex(ct);
    if (cm >= 0) add_unique(children_[size_t(m)], cm);
    visit(ct, depth + 1);
  }
}

std::vector<double> maximum_errors(const TileTopology& topo, const HeightField& field, int tx, int ty) {
  std::vector<double> eps_hat(size_t(topo.vertex_count()), 0.0);
  const int gi0 = tx * (topo.size() - 1), gj0 = ty * (topo.size() - 1);
  for (const BisectionTriangle& t : topo.roots()) max_errors_visit(topo, t, field, gi0, gj0, eps_hat);
  return eps_hat;
}

std::vector<double> incremental_errors(const TileTopology& topo, const HeightField& field, int tx, int ty) {
  const int n = topo.size(), gi0 = tx * (n - 1), gj0 = ty * (n - 1);
  std::vector<double> delta(size_t(topo.vertex_count()), 0.0);
  std::vector<std::pair<BisectionTriangle, int>> stack;
  for (const BisectionTriangle& t : topo.roots()) stack.push_back({t, 0});
  auto z = [&](int v) { return field.at(gi0 + v % n, gj0 + v / n); };
  while (!stack.empty()) {
    const BisectionTriangle t = stack.back().first;
    stack.pop_back();
    const int m = topo.split_vertex(t);
    if (m < 0) continue;
    // the triangle's plane at the hypotenuse's midpoint is the mean of its ends
    delta[size_t(m)] = std::max(delta[size_t(m)], std::abs(z(m) - 0.5 * (z(t.left) + z(t.right))));
    stack.push_back({TileTopology::child1(t, m), 0});
    stack.push_back({TileTopology::child2(t, m), 0});
  }
  return delta;
}

TerrainHierarchy::TerrainHierarchy(const HeightField& field, int tile_size, ErrorPropagation propagation,
                                   bool equalise_seams)
    : field_(&field), topo_(tile_size) {
  const int cells = tile_size - 1;
  if ((field.nx - 1) % cells != 0 || (field.ny - 1) % cells != 0 || field.nx < tile_size || field.ny < tile_size)
    throw std::invalid_argument("height field " + std::to_string(field.nx) + " x " + std::to_string(field.ny) +
                                " is not a whole number of tiles of " + std::to_string(tile_size));
  tiles_x_ = (field.nx - 1) / cells;
  tiles_y_ = (field.ny - 1) / cells;
  const int n = tile_size;
  errors_.resize(size_t(tiles_x_) * tiles_y_);
  for (int ty = 0; ty < tiles_y_; ++ty)
    for (int tx = 0; tx < tiles_x_; ++tx) {
      TileErrors& e = errors_[size_t(ty * tiles_x_ + tx)];
      e.eps_hat = maximum_errors(topo_, field, tx, ty);
      e.radius.assign(e.eps_hat.size(), 0.0);
      if (propagation == ErrorPropagation::kUnnested) {
        e.eps = incremental_errors(topo_, field, tx, ty);
        continue;  // no propagation, no balls: the broken variant
      }
      e.eps = e.eps_hat;
    }
  if (propagation == ErrorPropagation::kUnnested) return;
  // One saturation pass over a tile: children before parents, so one pass nests the whole tile.
  auto saturate = [&](int tx, int ty) {
    TileErrors& e = errors_[size_t(ty * tiles_x_ + tx)];
    for (int v : topo_.fine_to_coarse()) {
      const geometry::Vec3 pv = position(global_vertex(tx, ty, v));
      for (int c : topo_.children(v)) {
        e.eps[size_t(v)] = std::max(e.eps[size_t(v)], e.eps[size_t(c)]);
        const geometry::Vec3 d = position(global_vertex(tx, ty, c)) - pv;
        e.radius[size_t(v)] =
            std::max(e.radius[size_t(v)], std::sqrt(geometry::dot(d, d)) + e.radius[size_t(c)]);
      }
    }
  };
  // Makes the values of a vertex shared by two tiles equal (the larger); true when one changed.
  auto equalise = [&](TileErrors& a, int va, TileErrors& b, int vb) {
    bool changed = false;
    for (std::vector<double> TileErrors::*member : {&TileErrors::eps, &TileErrors::radius}) {
      double& x = (a.*member)[size_t(va)];
      double& y = (b.*member)[size_t(vb)];
      if (x != y) {
        x = y = std::max(x, y);
        changed = true;
      }
    }
    return changed;
  };
  // Bound on the passes: a pass that changes something raises a seam vertex's value, which the
  // next saturation carries to its DAG ancestors, strictly coarser (depth decreases by one per DAG
  // step, from at most 2 log2(n - 1) at the finest level); an ancestor on another seam (or a tile
  // corner) hands it on. Every hand-on happens at a strictly smaller depth, so a chain of passes
  // has at most one pass per depth level, 2 log2(n - 1), plus the first pass and the final pass that
  // finds nothing to change.
  int levels = 0;
  while ((1 << levels) < n - 1) ++levels;
  const int max_passes = 2 * levels + 2;
  for (seam_passes_ = 1;; ++seam_passes_) {
    for (int ty = 0; ty < tiles_y_; ++ty)
      for (int tx = 0; tx < tiles_x_; ++tx) saturate(tx, ty);
    if (!equalise_seams) break;
    bool changed = false;
    for (int ty = 0; ty < tiles_y_; ++ty)
      for (int tx = 0; tx < tiles_x_; ++tx) {
        TileErrors& a = errors_[size_t(ty * tiles_x_ + tx)];
        if (tx + 1 < tiles_x_) {  // east edge of a = west edge of b
          TileErrors& b = errors_[size_t(ty * tiles_x_ + tx + 1)];
          for (int j = 0; j < n; ++j) changed |= equalise(a, j * n + n - 1, b, j * n);
        }
        if (ty + 1 < tiles_y_) {  // north edge of a = south edge of b
          TileErrors& b = errors_[size_t((ty + 1) * tiles_x_ + tx)];
          for (int i = 0; i < n; ++i) changed |= equalise(a, (n - 1) * n + i, b, i);
        }
      }
    if (!changed) break;
    if (seam_passes_ >= max_passes)
      throw std::logic_error("seam equalisation needs more than " + std::to_string(max_passes) +
                             " passes (the bound 2 log2(n - 1) + 2)");
  }
}

int TerrainHierarchy::global_vertex(int tx, int ty, int v) const {
  const int n = topo_.size();
  return (ty * (n - 1) + v / n) * field_->nx + tx * (n - 1) + v % n;
}

geometry::Vec3 TerrainHierarchy::position(int g) const {
  const int gi = g % field_->nx, gj = g / field_->nx;
  return {gi * field_->spacing, gj * field_->spacing, field_->z[size_t(g)]};
}

}  // namespace ra::lod
