#include "scenes/scene_validation.h"

#include <cmath>
#include <sstream>

namespace ra::scenes {

std::vector<std::string> scene_problems(const Scene& scene, size_t max_problems) {
  std::vector<std::string> out;
  auto problem = [&](const std::string& what) {
    if (out.size() < max_problems) out.push_back(what);
  };
  const SceneLayout& l = scene.layout;
  for (size_t k = 0; k < scene.objects.size() && out.size() < max_problems; ++k) {
    const SceneObject& o = scene.objects[k];
    const StripMesh& m = o.mesh;
    const std::string who = "object " + std::to_string(k) + " (" + o.name + "): ";
    if (m.positions.size() % 3 != 0) problem(who + "positions not a multiple of 3");
    const size_t n = m.vertex_count();
    if (m.texcoords.size() != 2 * n)
      problem(who + std::to_string(m.texcoords.size()) + " texture coordinates for " +
              std::to_string(n) + " vertices");
    for (float f : m.positions)
      if (!std::isfinite(f)) {
        problem(who + "a position is not finite");
        break;
      }
    for (float f : m.texcoords)
      if (!std::isfinite(f)) {
        problem(who + "a texture coordinate is not finite");
        break;
      }
    for (size_t s = 0; s < m.strips.size(); ++s) {
      const TriangleStrip& st = m.strips[s];
      if (st.texture < 0 || static_cast<size_t>(st.texture) >= scene.textures.size())
        problem(who + "strip " + std::to_string(s) + " uses texture " + std::to_string(st.texture) +
                " of " + std::to_string(scene.textures.size()));
      for (uint32_t i : st.indices)
        if (i >= n) {
          problem(who + "strip " + std::to_string(s) + " index " + std::to_string(i) + " >= " +
                  std::to_string(n) + " vertices");
          break;
        }
    }
    // float positions against a double sphere: allow a relative 1e-4 of the radius and centre
    const double slack =
        1e-4 * (o.bounds.radius + std::sqrt(geometry::dot(o.bounds.centre, o.bounds.centre))) +
        1e-6;
    const double box_slack =
        1e-4 * (1 + std::sqrt(geometry::dot(l.box_max - l.box_min, l.box_max - l.box_min)));
    for (size_t i = 0; i < n; ++i) {
      const geometry::Vec3 v = m.vertex(i);
      if (!geometry::is_finite(v)) continue;
      const geometry::Vec3 d = v - o.bounds.centre;
      if (std::sqrt(geometry::dot(d, d)) > o.bounds.radius + slack) {
        std::ostringstream s;
        s << who << "vertex " << i << " at (" << v.x << ", " << v.y << ", " << v.z
          << ") lies outside the bounding sphere (radius " << o.bounds.radius << ")";
        problem(s.str());
        break;
      }
      if (v.x < l.box_min.x - box_slack || v.y < l.box_min.y - box_slack || v.z < l.box_min.z - box_slack ||
          v.x > l.box_max.x + box_slack || v.y > l.box_max.y + box_slack || v.z > l.box_max.z + box_slack) {
        std::ostringstream s;
        s << who << "vertex " << i << " at (" << v.x << ", " << v.y << ", " << v.z
          << ") lies outside the layout box";
        problem(s.str());
        break;
      }
    }
  }
  for (size_t t = 0; t < scene.textures.size(); ++t) {
    const Texture& tx = scene.textures[t];
    if (tx.width < 1 || tx.height < 1 || tx.rgba.size() != static_cast<size_t>(tx.width) * tx.height * 4)
      problem("texture " + std::to_string(t) + ": " + std::to_string(tx.rgba.size()) + " bytes for " +
              std::to_string(tx.width) + " x " + std::to_string(tx.height) + " texels");
  }
  return out;
}

}  // namespace ra::scenes
