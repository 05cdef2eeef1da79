// Table 5 of Wimmer & Wonka 2003 (section 7.1) for a generated scene.
#include "scenes/scene_statistics.h"

#include <cstdio>


namespace ra::scenes {
namespace {

// Binds drawing `mesh` after a strip with texture `bound` (-1: nothing bound yet).
int64_t binds_after(const StripMesh& mesh, int& bound) {
  int64_t n = 0;
  for (const TriangleStrip& s : mesh.strips) {
    if (s.indices.size() < 3) continue;  // draws nothing, binds nothing
    if (s.texture != bound) {
      ++n;
      bound = s.texture;
    }
  }
  return n;
}

}  // namespace

int64_t texture_binds(const StripMesh& mesh) {
  int bound = -1;
  return binds_after(mesh, bound);
}

int64_t scene_texture_binds(const Scene& scene) {
  int bound = -1;
  int64_t n = 0;
  for (const SceneObject& o : scene.objects) n += binds_after(o.mesh, bound);
  return n;
}

SceneStatistics scene_statistics(const Scene& scene, unsigned cache_size, CacheReset reset) {
  SceneStatistics s;
  s.cache_size = cache_size;
  s.objects = static_cast<int64_t>(scene.objects.size());
  for (const SceneObject& o : scene.objects) {
    s.triangles += static_cast<int64_t>(o.mesh.triangle_count());
    s.vertices += static_cast<int64_t>(o.mesh.vertex_count());
    s.transformed += transformed_vertices(o.mesh, cache_size, reset);
  }
  s.tv_per_triangle = s.triangles > 0 ? static_cast<double>(s.transformed) / s.triangles : 0.0;
  s.textures = static_cast<int64_t>(scene.textures.size());
  s.state_switches = scene_texture_binds(scene);
  s.triangles_per_switch =
      s.state_switches > 0 ? static_cast<double>(s.triangles) / s.state_switches : 0.0;
  return s;
}

}  // namespace ra::scenes
