// Levels of detail by meshoptimizer's simplifier (lod_chain.h).
#include "regulation/lod_chain.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <map>
#include <stdexcept>
#include <unordered_map>

#include "scenes/vertex_cache.h"

namespace ra::regulation {
namespace {

constexpr unsigned kNoRestart = 0xFFFFFFFFu;  // never an index: unstripify sees plain strips

// The object's triangles per texture, degenerate ones dropped.
std::map<int, std::vector<unsigned>> triangle_lists(const scenes::StripMesh& mesh) {
  std::map<int, std::vector<unsigned>> out;
  for (const scenes::TriangleStrip& s : mesh.strips) {
    if (s.indices.size() < 3) continue;
    std::vector<unsigned> tri(meshopt_unstripifyBound(s.indices.size()));
    tri.resize(meshopt_unstripify(tri.data(), s.indices.data(), s.indices.size(), kNoRestart));
    auto& dst = out[s.texture];
    dst.insert(dst.end(), tri.begin(), tri.end());
  }
  return out;
}

// A mesh of `strips` over the vertices they reference only (renumbered in first-use order).
scenes::StripMesh compacted(const scenes::StripMesh& src,
                            const std::vector<scenes::TriangleStrip>& strips) {
  scenes::StripMesh out;
  std::unordered_map<uint32_t, uint32_t> remap;
  for (const scenes::TriangleStrip& s : strips) {
    scenes::TriangleStrip t;
    t.texture = s.texture;
    for (uint32_t i : s.indices) {
      auto [it, fresh] = remap.emplace(i, uint32_t(remap.size()));
      if (fresh) {
        out.positions.insert(out.positions.end(), src.positions.begin() + 3 * i, src.positions.begin() + 3 * i + 3);
        out.texcoords.insert(out.texcoords.end(), src.texcoords.begin() + 2 * i, src.texcoords.begin() + 2 * i + 2);
      }
      t.indices.push_back(it->second);
    }
    out.strips.push_back(std::move(t));
  }
  return out;
}

int64_t referenced_vertices(const scenes::StripMesh& m) {
  std::vector<bool> used(m.vertex_count(), false);
  int64_t n = 0;
  for (const scenes::TriangleStrip& s : m.strips)
    for (uint32_t i : s.indices)
      if (!used[i]) used[i] = true, ++n;
  return n;
}

}  // namespace

LodChain build_lod_chain(const scenes::SceneObject& object, const std::vector<double>& ratios,
                         unsigned cache_size) {
  if (ratios.empty() || ratios.front() != 1.0)
    throw std::invalid_argument("LOD ratios must start with 1");
  for (std::size_t k = 1; k < ratios.size(); ++k)
    if (!(ratios[k] > 0 && ratios[k] < ratios[k - 1]))
      throw std::invalid_argument("LOD ratios must decrease and stay above 0");
  const scenes::StripMesh& mesh = object.mesh;
  LodChain chain;
  chain.name = object.name;
  chain.bounds = object.bounds;

  const auto lists = triangle_lists(mesh);
  int64_t triangles0 = 0;
  for (const auto& [tex, idx] : lists) triangles0 += int64_t(idx.size() / 3);
  LodLevel l0;
  l0.mesh = mesh;
  l0.triangles = triangles0;
  l0.vertices = referenced_vertices(mesh);
  l0.transformed = scenes::transformed_vertices(mesh, cache_size);
  chain.levels.push_back(std::move(l0));

  const std::size_t nv = mesh.vertex_count();
  const float scale = nv ? meshopt_simplifyScale(mesh.positions.data(), nv, 3 * sizeof(float)) : 0.f;
  for (std::size_t k = 1; k < ratios.size(); ++k) {
    std::vector<scenes::TriangleStrip> strips;
    int64_t triangles = 0;
    double rel_error = 0;
    for (const auto& [tex, idx] : lists) {
      // keep at least one triangle per texture group: a tree keeps its trunk
      const std::size_t target = std::max<std::size_t>(3, std::size_t(double(idx.size() / 3) * ratios[k] + 0.5) * 3);
      std::vector<unsigned> out(idx.size());
      float err = 0;
      out.resize(meshopt_simplify(out.data(), idx.data(), idx.size(), mesh.positions.data(), nv,
                                  3 * sizeof(float), target, 1.0f /* no error limit */, 0, &err));
      if (out.empty()) continue;
      rel_error = std::max(rel_error, double(err));
      triangles += int64_t(out.size() / 3);
      std::vector<unsigned> strip(meshopt_stripifyBound(out.size()));
      strip.resize(meshopt_stripify(strip.data(), out.data(), out.size(), nv, 0u /* degenerate joins */));
      strips.push_back({std::vector<uint32_t>(strip.begin(), strip.end()), tex});
    }
    if (triangles >= chain.levels.back().triangles || triangles == 0) continue;  // no further reduction
    LodLevel l;
    l.target_ratio = ratios[k];
    l.mesh = compacted(mesh, strips);
    l.triangles = triangles;
    l.vertices = int64_t(l.mesh.vertex_count());
    l.transformed = scenes::transformed_vertices(l.mesh, cache_size);
    l.simplifier_error_m = rel_error * double(scale);
    l.error_m = std::max(l.simplifier_error_m, chain.levels.back().error_m);
    chain.levels.push_back(std::move(l));
  }
  return chain;
}

}  // namespace ra::regulation
