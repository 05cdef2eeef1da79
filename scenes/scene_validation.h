// Invariants every generated or loaded scene must satisfy before it is drawn or measured.
// Units: metres, world coordinates, +Z up.
#pragma once

#include <string>
#include <vector>

#include "scenes/scene.h"

namespace ra::scenes {

// What is wrong with `scene`, one line per problem, empty when nothing is: positions and texture
// coordinates finite and of the right count, every strip index in range, every texture index in
// range, textures of width * height * 4 bytes, every bounding sphere enclosing all of its
// object's vertices (with 1e-4 relative slack for float rounding), and the layout box holding
// every vertex. Reports at most `max_problems` lines.
// Used by tests as an independent check of every generated scene.
std::vector<std::string> scene_problems(const Scene& scene, size_t max_problems = 20);

}  // namespace ra::scenes
