// GL drawing of the terrain for the LOD study: the whole height field uploaded once as a vertex
// buffer (x y z floats, RGBA8 colour), each frame's mesh drawn as one GL_TRIANGLE_STRIP per tile
// from an index buffer, through a GL platform into a window-sized RGBA8 buffer with a 24-bit
// depth buffer (scenes/scene_target.h); fixed function, depth test on, no lighting in GL.
//
// Shading (chosen so that geometric differences show): each vertex carries a colour computed once
// on the CPU from the full-resolution surface: a height-coded ramp (green, brown, grey, white)
// times a Lambert term of a fixed sun (from the north-west, 45 degrees up) on the full-resolution
// normal (central differences), plus 0.25 ambient. The LOD mesh interpolates these colours over
// its larger triangles and its surface sits at other depths, so the image difference against the
// full mesh measures both what the eye sees change and where silhouettes move.
//
// Timing: the steady clock read before glClear and after glFinish (the pipeline idle before,
// glFinish), i.e. a whole frame: clear + the tiles' strips. The index upload happens before the
// clock starts. Mesa picks its driver when the first context of a process is made: one platform
// per process.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "scenes/scene.h"
#include "terrain_lod/height_field.h"
#include "terrain_lod/lod_refinement.h"
#include "scenes/camera.h"

namespace ra::lod {

struct ImageDifference {
  double mean_abs = 0;         // mean over pixels and R, G, B of |a - b|, 0..255 levels
  double differing = 0;        // fraction of pixels whose largest channel difference > 16 levels
};

ImageDifference image_difference(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b);

class LodRenderer {
 public:
  // Throws UserError for a platform without a Mesa driver, std::runtime_error when GL fails.
  LodRenderer(const std::string& platform, const scenes::CameraSettings& cam,
              const HeightField& field);
  ~LodRenderer();
  LodRenderer(const LodRenderer&) = delete;
  LodRenderer& operator=(const LodRenderer&) = delete;

  std::string gl_renderer() const;  // GL_RENDERER
  std::string gl_version() const;   // GL_VERSION

  void set_viewpoint(const scenes::Viewpoint& vp);
  // Uploads the mesh's strips (untimed).
  void upload(const LodMesh& mesh);
  // One timed frame of the uploaded mesh; returns microseconds (CPU, clear + draw + glFinish).
  double draw();
  // The last frame's image: width * height RGBA8, rows bottom-up.
  const std::vector<uint8_t>& image() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ra::lod
