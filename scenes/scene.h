// A scene for the rendering-time study (Wimmer & Wonka 2003, section 7.1): objects made of lists of
// indexed triangle strips, each strip with its own texture, as the paper's city, terrain and forest.
// Units: metres, world coordinates, right-handed, +Z up (the ground is the plane z = 0).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "geometry/vector_math.h"

namespace ra::scenes {

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
  size_t index_count() const;     // sum over strips of their index counts (what glDrawElements reads)
  geometry::Vec3 vertex(size_t i) const {  // metres, world coordinates
    return {positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]};
  }
};

struct BoundingSphere {
  geometry::Vec3 centre;  // metres, world coordinates
  double radius = 0;  // metres
};

// The smallest sphere about the centre of the vertices' axis-aligned box that holds every vertex
// (not the minimal sphere: at most sqrt(3) times its radius, and cheap). Radius 0 for no vertices.
BoundingSphere enclosing_sphere(const StripMesh& mesh);

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

// What a camera path needs to know of a scene's layout; the generators fill it.
// Units: metres, world coordinates, +Z up.
struct SceneLayout {
  geometry::Vec3 box_min, box_max;  // axis-aligned box holding every vertex of every object
  // City streets: centre lines at x = street_x0 + i * street_pitch (i = 0..streets_x - 1) and at
  // y = street_y0 + j * street_pitch (j = 0..streets_y - 1); street_width is kerb to kerb.
  double street_x0 = 0, street_y0 = 0, street_pitch = 0, street_width = 0;
  int streets_x = 0, streets_y = 0;  // 0: the scene has no streets
  // Ground heights of a regular grid (terrain): ground_nx * ground_ny values, row-major with x
  // fastest, vertex (i, j) at (ground_x0 + i * ground_spacing, ground_y0 + j * ground_spacing).
  // Empty: the ground is the plane z = 0.
  double ground_x0 = 0, ground_y0 = 0, ground_spacing = 0;
  int ground_nx = 0, ground_ny = 0;
  std::vector<float> ground_z;

  // An upper bound of the ground surface at (x, y): the highest corner of the grid cell holding
  // the point (points outside the grid are clamped to it); 0 without a grid. Metres.
  double ground_ceiling(double x, double y) const;
};

struct Scene {
  std::string kind;  // "city", "terrain", "forest"
  std::vector<SceneObject> objects;
  std::vector<Texture> textures;
  SceneLayout layout;
};

// FNV-1a over the kind, every object's name, positions, texture coordinates, strips, bounds, and
// the textures: the determinism check (same seed, same hash). The generators draw their random
// numbers with integer arithmetic only (scenes/scene_rng.h), so a scene differs between machines
// only if their libm's sin/cos differ in the last place of a double and that changes a float.
uint64_t scene_hash(const Scene& scene);

// One camera position of a path: where the eye is and where it looks.
struct Viewpoint {
  geometry::Vec3 eye;             // metres, world coordinates
  geometry::Vec3 target;          // a point the camera looks at
  geometry::Vec3 up = {0, 0, 1};  // world up
};

}  // namespace ra::scenes
