// FIFO vertex-cache counts: hand-computed cases, and meshoptimizer against a brute-force FIFO.
#include "scenes/vertex_cache.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <deque>
#include <stdexcept>

#include "scenes/scene_rng.h"
#include "scenes/strip_builder.h"

namespace ra::scenes {
namespace {

StripMesh mesh_with(size_t vertices, std::vector<std::vector<uint32_t>> strips) {
  StripMesh m;
  for (size_t i = 0; i < vertices; ++i) add_vertex(m, {double(i), 0, 0}, 0, 0);
  for (auto& s : strips) m.strips.push_back({std::move(s), 0});
  return m;
}

// The reference: what the strip hardware does, written without meshoptimizer. Every index of
// every drawn strip is looked up once; a miss transforms the vertex and enqueues it, evicting the
// oldest entry when the queue is full; hits change nothing.
int64_t brute_force_fifo(const StripMesh& m, unsigned cache_size, bool reset_per_strip) {
  std::deque<uint32_t> fifo;
  int64_t transformed = 0;
  for (const TriangleStrip& s : m.strips) {
    if (s.indices.size() < 3) continue;
    if (reset_per_strip) fifo.clear();
    for (uint32_t i : s.indices) {
      if (std::find(fifo.begin(), fifo.end(), i) != fifo.end()) continue;
      ++transformed;
      fifo.push_back(i);
      if (fifo.size() > cache_size) fifo.pop_front();
    }
  }
  return transformed;
}

// (a) A strip of n distinct vertices transforms each exactly once, whatever the cache (>= 3).
TEST(VertexCache, SingleStripTransformsEachVertexOnce) {
  for (unsigned n : {3u, 4u, 10u, 101u}) {
    std::vector<uint32_t> idx(n);
    for (unsigned i = 0; i < n; ++i) idx[i] = i;
    const StripMesh m = mesh_with(n, {idx});
    for (unsigned cache : {3u, 4u, 16u, 32u, 1000u}) {
      EXPECT_EQ(transformed_vertices(m, cache), n) << "n " << n << " cache " << cache;
      EXPECT_EQ(transformed_vertices(m, cache, CacheReset::kPerStrip), n);
    }
  }
}

// (b1) A 2 x 6 vertex grid (one row band, 10 triangles) as one strip: 12 transforms, 1.2 per tri.
TEST(VertexCache, TwoRowGridStrip) {
  StripMesh m;
  add_grid(m, {0, 0, 0}, {5, 0, 0}, {0, 1, 0}, 5, 1, 0, 0, 1, 0, 1);
  ASSERT_EQ(m.strips.size(), 1u);
  EXPECT_EQ(m.triangle_count(), 10u);
  EXPECT_EQ(transformed_vertices(m, 16), 12);
  EXPECT_EQ(transformed_vertices(m, 3), 12);
}

// (b2) A 4 x 3 vertex grid (v(r, c) = 4 r + c) as two row strips:
//   strip A (rows 0-1): 4 0 5 1 6 2 7 3       strip B (rows 1-2): 8 4 9 5 10 6 11 7
// cache 16: A transforms 8; B finds 4 5 6 7 still cached and transforms 8 9 10 11: 12.
// cache 12 or 9: B's first miss (8) leaves 4 in the FIFO; 4 hits, 9 evicts it, 5 hits, 10 evicts
//   0, 6 hits, ...: B transforms only 8 9 10 11: 12.
// cache 8: A fills the FIFO exactly; B's miss on 8 evicts 4, its look-up of 4 then misses and
//   evicts 0... every look-up of B misses: 8 + 8 = 16 (FIFO's pathology: a bigger row reuse
//   needs more than one row band of room).
// cache 4: after A the FIFO holds 6 2 7 3; B misses everything: 16.
// With the cache reset per strip every case is 8 + 8 = 16.
TEST(VertexCache, GridOfTwoRowStripsByHand) {
  StripMesh m;
  add_grid(m, {0, 0, 0}, {3, 0, 0}, {0, 2, 0}, 3, 2, 0, 0, 1, 0, 1);
  ASSERT_EQ(m.strips.size(), 2u);
  ASSERT_EQ(m.strips[0].indices, (std::vector<uint32_t>{4, 0, 5, 1, 6, 2, 7, 3}));
  ASSERT_EQ(m.strips[1].indices, (std::vector<uint32_t>{8, 4, 9, 5, 10, 6, 11, 7}));
  EXPECT_EQ(transformed_vertices(m, 4), 16);
  EXPECT_EQ(transformed_vertices(m, 8), 16);
  EXPECT_EQ(transformed_vertices(m, 9), 12);
  EXPECT_EQ(transformed_vertices(m, 12), 12);
  EXPECT_EQ(transformed_vertices(m, 16), 12);
  for (unsigned cache : {4u, 8u, 9u, 16u})
    EXPECT_EQ(transformed_vertices(m, cache, CacheReset::kPerStrip), 16) << cache;
}

// The cache persists across strips with different textures (the state change does not flush the
// model's cache) and restarts with every mesh (object).
TEST(VertexCache, KeptAcrossTexturesResetPerMesh) {
  StripMesh m = mesh_with(5, {{0, 1, 2, 3}, {2, 3, 4}});
  m.strips[1].texture = 1;
  EXPECT_EQ(transformed_vertices(m, 16), 5);
  EXPECT_EQ(transformed_vertices(m, 16, CacheReset::kPerStrip), 7);
  // a second call starts empty again: no state survives between meshes
  EXPECT_EQ(transformed_vertices(m, 16), 5);
}

// Why the strip's own index stream and not meshopt_unstripify's list: strip a b c d a e f
// (0 1 2 3 0 4 5) with a 4-entry FIFO. The strip looks up 0 1 2 3 (4 misses), 0 (hit, the oldest
// entry), 4 (miss, evicts 0), 5 (miss): 6. The list (0 1 2)(2 1 3)(2 3 0)(0 3 4)(0 4 5) looks 0
// up again after 4 evicted it: 7, a transform the strip never causes.
TEST(VertexCache, StripStreamVersusTriangleList) {
  const StripMesh m = mesh_with(6, {{0, 1, 2, 3, 0, 4, 5}});
  EXPECT_EQ(transformed_vertices(m, 4), 6);
  EXPECT_EQ(brute_force_fifo(m, 4, false), 6);
  EXPECT_EQ(transformed_vertices_as_triangle_list(m, 4), 7);
}

// Strips of fewer than 3 indices draw nothing and cost nothing; an empty mesh transforms nothing.
TEST(VertexCache, ShortStripsAndEmptyMesh) {
  EXPECT_EQ(transformed_vertices(StripMesh{}, 16), 0);
  const StripMesh m = mesh_with(6, {{0, 1}, {}, {2, 3, 4}, {5}});
  EXPECT_EQ(transformed_vertices(m, 16), 3);
  EXPECT_EQ(transformed_vertices(m, 16, CacheReset::kPerStrip), 3);
}

TEST(VertexCache, RejectsTinyCacheAndBadIndices) {
  const StripMesh m = mesh_with(3, {{0, 1, 2}});
  EXPECT_THROW(transformed_vertices(m, 2), std::invalid_argument);
  const StripMesh bad = mesh_with(3, {{0, 1, 3}});
  EXPECT_THROW(transformed_vertices(bad, 16), std::out_of_range);
}

// (c) meshoptimizer's count equals the brute-force FIFO on random strip meshes (repeated and
// degenerate indices included), with the cache kept per mesh and reset per strip.
TEST(VertexCache, MeshoptimizerAgreesWithBruteForceFifo) {
  int compared = 0;
  for (uint64_t trial = 0; trial < 200; ++trial) {
    SceneRng rng(2003, ScenePurpose::kCameraWaypoint, trial);
    const size_t vertices = static_cast<size_t>(rng.integer(3, 60));
    std::vector<std::vector<uint32_t>> strips(static_cast<size_t>(rng.integer(1, 6)));
    for (auto& s : strips) {
      const int64_t len = rng.integer(0, 80);
      // a local window of vertex numbers makes reuse (hits) common, as in real meshes
      for (int64_t k = 0; k < len; ++k) {
        const int64_t centre = k * static_cast<int64_t>(vertices) / std::max<int64_t>(1, len);
        const int64_t v = std::clamp<int64_t>(centre + rng.integer(-6, 6), 0, vertices - 1);
        s.push_back(static_cast<uint32_t>(v));
      }
    }
    const StripMesh m = mesh_with(vertices, strips);
    for (unsigned cache : {3u, 4u, 8u, 16u, 24u, 32u}) {
      ASSERT_EQ(transformed_vertices(m, cache), brute_force_fifo(m, cache, false))
          << "trial " << trial << " cache " << cache;
      ASSERT_EQ(transformed_vertices(m, cache, CacheReset::kPerStrip), brute_force_fifo(m, cache, true))
          << "trial " << trial << " cache " << cache;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 1200);
}

}  // namespace
}  // namespace ra::scenes
