// FIFO post-transform vertex cache counts for strip meshes (Wimmer & Wonka 2003, section 3: "the
// number of actually transformed vertices"), computed by meshoptimizer's analyser.
#include "scenes/vertex_cache.h"

#include <meshoptimizer.h>

#include <cassert>
#include <stdexcept>
#include <string>
#include <vector>

namespace ra::scenes {
namespace {

void check_cache(unsigned cache_size) {
  // meshopt_analyzeVertexCache asserts cache_size >= 3; a strip needs its last two vertices anyway
  if (cache_size < 3)
    throw std::invalid_argument("vertex cache size " + std::to_string(cache_size) +
                                " is out of range (allowed: 3 or more)");
}

// A FIFO count of one index stream: warp_size 0 and primgroup_size 0 switch off meshoptimizer's
// warp and primitive-group flushes, leaving a cache_size-entry FIFO that looks each index up once.
int64_t fifo_count(std::vector<unsigned>& stream, size_t vertex_count, unsigned cache_size) {
  if (stream.empty()) return 0;
  // the analyser reads triangles; repeating the last index is always a hit (nothing entered the
  // FIFO since it was looked up), so the padding transforms nothing
  while (stream.size() % 3 != 0) stream.push_back(stream.back());
  const meshopt_VertexCacheStatistics s =
      meshopt_analyzeVertexCache(stream.data(), stream.size(), vertex_count, cache_size, 0, 0);
  return static_cast<int64_t>(s.vertices_transformed);
}

}  // namespace

int64_t transformed_vertices(const StripMesh& mesh, unsigned cache_size, CacheReset reset) {
  check_cache(cache_size);
  const size_t n = mesh.vertex_count();
  std::vector<unsigned> stream;
  stream.reserve(mesh.index_count() + 2);
  int64_t total = 0;
  for (const TriangleStrip& s : mesh.strips) {
    if (s.indices.size() < 3) continue;  // draws nothing: GL reads no vertex of it
    for (uint32_t i : s.indices)
      if (i >= n)
        throw std::out_of_range("strip index " + std::to_string(i) + " >= vertex count " +
                                std::to_string(n));
    stream.insert(stream.end(), s.indices.begin(), s.indices.end());
    if (reset == CacheReset::kPerStrip) {
      total += fifo_count(stream, n, cache_size);
      stream.clear();
    }
  }
  return total + fifo_count(stream, n, cache_size);
}

int64_t transformed_vertices_as_triangle_list(const StripMesh& mesh, unsigned cache_size) {
  check_cache(cache_size);
  const size_t n = mesh.vertex_count();
  std::vector<unsigned> list;
  for (const TriangleStrip& s : mesh.strips) {
    if (s.indices.size() < 3) continue;
    for (uint32_t i : s.indices)
      if (i >= n)
        throw std::out_of_range("strip index " + std::to_string(i) + " >= vertex count " +
                                std::to_string(n));
    std::vector<unsigned> tri(meshopt_unstripifyBound(s.indices.size()));
    // restart_index ~0u: no vertex has that number (vertex counts are below 2^32 - 1)
    const size_t k = meshopt_unstripify(tri.data(), s.indices.data(), s.indices.size(), ~0u);
    list.insert(list.end(), tri.begin(), tri.begin() + static_cast<std::ptrdiff_t>(k));
  }
  if (list.empty()) return 0;
  const meshopt_VertexCacheStatistics st =
      meshopt_analyzeVertexCache(list.data(), list.size(), n, cache_size, 0, 0);
  return static_cast<int64_t>(st.vertices_transformed);
}

}  // namespace ra::scenes
