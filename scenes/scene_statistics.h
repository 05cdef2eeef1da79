// The descriptive values of a test scene, as Table 5 of Wimmer & Wonka 2003 (section 7.1):
// objects, triangles, transformed vertices with a FIFO vertex cache, textures, and the texture
// state switches of drawing every object strip by strip in order. Counts are dimensionless.
#pragma once

#include <cstdint>
#include <string>

#include "scenes/scene.h"
#include "scenes/vertex_cache.h"

namespace ra::scenes {

struct SceneStatistics {
  unsigned cache_size = 0;           // FIFO entries the #tv count assumed
  int64_t objects = 0;               // #objects: what culling handles (Scene::objects)
  int64_t triangles = 0;             // #triangles: all strips' triangles, degenerate included
  int64_t vertices = 0;              // distinct vertices stored (sum of vertex_count())
  int64_t transformed = 0;           // #tv: transformed_vertices per object, summed
  double tv_per_triangle = 0;        // #tv / tri; 0 without triangles (a strip's best ~0.5-1)
  int64_t textures = 0;              // #textures: Scene::textures.size()
  int64_t state_switches = 0;        // #sw: texture binds, the first one included
  double triangles_per_switch = 0;   // tri / sw; 0 without switches
};

// Statistics of `scene` with a cache of `cache_size` (>= 3) entries, reset per object.
SceneStatistics scene_statistics(const Scene& scene, unsigned cache_size,
                                 CacheReset reset = CacheReset::kPerMesh);

// Texture binds drawing one mesh alone: 1 for its first drawn strip, +1 at every change of
// texture between consecutive drawn strips (strips of < 3 indices draw nothing).
// Used by tests as an independent check of scene_texture_binds, mesh by mesh.
int64_t texture_binds(const StripMesh& mesh);

// Texture binds drawing every object of `scene` in order, state carried across objects (Table
// 5's #state switches: the forest's 157 trees with bark and leaves give 314).
int64_t scene_texture_binds(const Scene& scene);

}  // namespace ra::scenes
