// Levels of detail of one scene object, made with meshoptimizer's simplifier (Debian's
// libmeshoptimizer-dev 0.18, meshopt_simplify: edge collapses under a quadric error metric,
// Garland & Heckbert 1997), for the regulation study (Horvitz & Lengyel 1997, section 2: "the
// dynamic selection of simpler models from a spectrum of models").
//
// Level 0 is the object as generated (its own strips). Level k > 0 is simplified from level 0 at
// the target ratio r_k of its triangles, separately per texture (the object's strips grouped by
// texture, converted to triangle lists with meshopt_unstripify, degenerate triangles dropped), so
// that every triangle keeps its texture; each group's result is restripified (meshopt_stripify,
// strips joined by degenerate triangles: one strip per texture, as a GL_TRIANGLE_STRIP draw wants)
// and the level's vertices compacted to those it references.
//
// Per level: triangles (non-degenerate), vertices (referenced), transformed vertices (#tv: FIFO
// cache model of scenes/vertex_cache.h on the level's strips) and the geometric error in metres:
// meshopt_simplify's result_error (relative to the mesh extent) times meshopt_simplifyScale of the
// object's vertices, the largest over the texture groups. A chain is monotone: a level whose
// triangle count is not below its predecessor's (the simplifier could not go further) is dropped,
// and a level's error is the largest of its own and its predecessors' (a coarser level is never
// reported as more accurate; the simplifier works from level 0 each time and can, rarely, stop at
// a smaller error with fewer triangles).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace ra::regulation {

struct LodLevel {
  double target_ratio = 1;     // the ratio asked for (triangles of level 0 x ratio)
  scenes::StripMesh mesh;      // the level's strips and (compacted) vertices, world coordinates
  int64_t triangles = 0;       // non-degenerate triangles
  int64_t vertices = 0;        // vertices the strips reference
  int64_t transformed = 0;     // #tv, FIFO post-transform cache of `cache_size` entries
  double error_m = 0;          // geometric error, metres; 0 at level 0, non-decreasing
  double simplifier_error_m = 0;  // what the simplifier reported for this level, metres
};

struct LodChain {
  std::string name;       // the scene object's
  // Of level 0 (every level lies within it: simplification keeps vertices).
  scenes::BoundingSphere bounds;
  std::vector<LodLevel> levels;  // level 0 first; triangles decreasing, error non-decreasing
};

// `ratios`: 1 first, then decreasing values in (0, 1). `cache_size` >= 3.
// Throws std::invalid_argument on bad ratios.
LodChain build_lod_chain(const scenes::SceneObject& object, const std::vector<double>& ratios,
                         unsigned cache_size);

}  // namespace ra::regulation
