// A scene for the rendering-time study (Wimmer & Wonka 2003, section 7.1): objects made of lists of
// indexed triangle strips, each strip with its own texture, as the paper's city, terrain and forest.
// Units: metres, world coordinates, right-handed, +Z up (the ground is the plane z = 0).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "runner/vector_math.h"

namespace ra {

// One indexed triangle strip; triangle k is (i[k], i[k+1], i[k+2]) with the winding of odd k
// reversed, as GL_TRIANGLE_STRIP draws it.
struct TriangleStrip {
  std::vector<uint32_t> indices;  // into StripMesh::positions / texcoords (vertex numbers)
  int texture = 0;                // index into Scene::textures
};

// Vertices in world coordinates (objects are placed by the generator, not by a matrix).
struct StripMesh {
  std::vector<float> positions;  // x, y, z per vertex, metres
  std::vector<float> texcoords;  // s, t per vertex (dimensionless, may exceed [0, 1]: repeat)
  std::vector<TriangleStrip> strips;

  size_t vertex_count() const { return positions.size() / 3; }
  size_t triangle_count() const;  // sum over strips of max(0, indices - 2), degenerate ones included
};

struct BoundingSphere {
  Vec3 centre;        // metres, world coordinates
  double radius = 0;  // metres
};

struct SceneObject {
  std::string name;  // e.g. "building 12", "tree 3", "terrain"
  StripMesh mesh;
  BoundingSphere bounds;  // encloses every vertex
};

// A small procedural RGBA8 texture (the study needs texture state changes, not pretty pictures).
struct Texture {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;  // width * height * 4 bytes, rows bottom-up
};

struct Scene {
  std::string kind;  // "city", "terrain", "forest"
  std::vector<SceneObject> objects;
  std::vector<Texture> textures;
};

// One camera position of a path: where the eye is and where it looks.
struct Viewpoint {
  Vec3 eye;                // metres, world coordinates
  Vec3 target;             // a point the camera looks at
  Vec3 up = {0, 0, 1};     // world up
};

}  // namespace ra
