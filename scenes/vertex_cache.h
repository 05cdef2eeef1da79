// Transformed vertices (#tv of Wimmer & Wonka 2003, sections 3 and 7.1): how many vertices the
// GPU's post-transform cache makes it transform, modelled as a FIFO of `cache_size` entries.
//
// The model. GL_TRIANGLE_STRIP reads each index once, in order; an index found among the last
// cache_size vertices transformed is a hit, otherwise the vertex is transformed and enters the
// FIFO, pushing the oldest out (a hit does not refresh an entry). The cache is empty when an
// object (a StripMesh) starts and carries over between the strips of one object, texture
// changes included, as when an object's strips are drawn back to back (the per-object #tv the
// study fits); CacheReset::kPerStrip empties it before every strip instead (every strip its own
// glDrawElements on hardware that flushes between draws), an upper bound.
//
// meshoptimizer's meshopt_analyzeVertexCache does the counting: with warp_size 0 and
// primgroup_size 0 it is a plain FIFO over its index stream, looking each index up once. We give
// it the strips' own index stream (padded to a multiple of 3 with the last index, always a hit),
// not meshopt_unstripify's triangle list: the list looks each strip vertex up three times, and a
// vertex that hit as the oldest entry can be evicted before its second look-up, which counts a
// transform the strip never causes (see vertex_cache_test.cpp, StripStreamVersusTriangleList).
#pragma once

#include <cstdint>

#include "scenes/scene.h"

namespace ra::scenes {

enum class CacheReset {
  kPerMesh,   // empty at the start of the mesh (object), kept across its strips (the default)
  kPerStrip,  // empty at the start of every strip
};

// Vertices transformed drawing mesh's strips in order as GL_TRIANGLE_STRIP with a FIFO
// post-transform cache of cache_size entries (>= 3; a GeForce3 had about 16 to 24).
// Strips with fewer than 3 indices draw nothing and are skipped.
int64_t transformed_vertices(const StripMesh& mesh, unsigned cache_size,
                             CacheReset reset = CacheReset::kPerMesh);

// The same mesh converted to a triangle list with meshopt_unstripify (degenerate triangles
// dropped) and analysed as a list, each triangle looking up its three vertices: what a renderer
// drawing GL_TRIANGLES would transform. For comparison only; not the strip model.
// Used by tests as an independent check of the strip model (meshoptimizer on a list).
int64_t transformed_vertices_as_triangle_list(const StripMesh& mesh, unsigned cache_size);

}  // namespace ra::scenes
