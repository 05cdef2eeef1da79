// GL measurement of the rendering-time study (Wimmer & Wonka 2003, sections 4.2 and 7.1): a scene
// uploaded to an OSMesa context (llvmpipe or softpipe) and drawn as the paper drew its scenes:
// per object its lists of indexed triangle strips from buffer objects (VBO + index buffer, one
// glDrawRangeElements(GL_TRIANGLE_STRIP) per strip), one glBindTexture per change of strip texture
// (a state switch), depth test on, texturing on (GL_REPLACE, bilinear, repeat), no lighting.
//
// Timing of a draw, both per repetition (every repetition is kept by the caller):
// - CPU: the steady clock read before the first GL command of the draw and after glFinish, the
//   pipeline idle before it (glFinish), as the paper timed ("synchronizing the pipeline (using the
//   glFinish instruction) and reading the processor clock cycle counter both before and after").
// - GPU: a GL_TIME_ELAPSED query (ARB_timer_query) around the same commands, when the extension
//   string lists GL_ARB_timer_query and GL_QUERY_COUNTER_BITS for it is > 0; its result is in
//   nanoseconds. The query's begin/end are inside the CPU interval (they are part of what the CPU
//   time measures).
// Pixels (#pix): GL_SAMPLES_PASSED of the object drawn alone with the depth test off, in an untimed
// pass: every fragment its triangles generate inside the window, i.e. the pixels of its projection,
// a pixel counted once per triangle of the object covering it (the rasterizer's work; with the
// depth test on, fragments hidden by the object's own nearer triangles would be missed although
// they are rasterized, and every count would need a clear of the depth buffer).
//
// Mesa picks its driver (GALLIUM_DRIVER) when the first context of a process is made: make the
// SceneRenderer before any other GL call of the process, one platform per process
// (timing_study.h runs each platform in a child process).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "scenes/scene.h"
#include "scenes/camera.h"

namespace ra::timing {

struct RendererInfo {
  std::string platform;        // e.g. "osmesa-llvmpipe"
  std::string gallium_driver;  // the Mesa driver asked for (PlatformSpec::mesa_driver); "" for a device
  std::string backend;         // how the context was made (GlContext::backend())
  std::string lp_num_threads;  // LP_NUM_THREADS as Mesa saw it
  std::string renderer, version, vendor;  // glGetString
  bool timer_query = false;    // GL_ARB_timer_query listed and GL_QUERY_COUNTER_BITS > 0
  bool timer_query_listed = false;  // the extension string lists GL_ARB_timer_query
  int timer_query_bits = 0;    // GL_QUERY_COUNTER_BITS of GL_TIME_ELAPSED (0: no timer)
  int depth_bits = 0;          // of the depth renderbuffer
};

// One repetition of a timed draw.
struct DrawTime {
  double cpu_us = 0;  // steady clock, draw + glFinish
  double gpu_us = 0;  // GL_TIME_ELAPSED / 1000; NaN when not measured
};

class SceneRenderer {
 public:
  // Makes the context of `platform` (an OSMesa platform of platforms/platform.h; sets GALLIUM_DRIVER
  // and LP_NUM_THREADS=0 unless already set), a framebuffer object of cam.width x cam.height with
  // RGBA8 colour and 24-bit depth. `gpu_timer`: use GL_TIME_ELAPSED when supported.
  // Throws ra::util::UserError for a platform without a Mesa driver, std::runtime_error when GL fails.
  SceneRenderer(const std::string& platform, const scenes::CameraSettings& cam,
                bool gpu_timer = true);
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  const RendererInfo& info() const;
  const scenes::CameraSettings& camera() const;
  bool measuring_gpu() const;  // GL_TIME_ELAPSED queries are issued

  // Uploads `scene` (replacing the previous one): per object a vertex buffer (x y z s t floats)
  // and an index buffer holding its strips; every texture. Keeps no pointer into `scene`.
  void upload(const scenes::Scene& scene);

  // Sets the modelview matrix of `vp` (the projection is the camera's).
  void set_viewpoint(const scenes::Viewpoint& vp);

  // One timed repetition. `with_clear`: the colour and depth clear is part of the timed commands
  // (a whole frame); otherwise it is done and finished before the clock starts (one object
  // measured alone). Texture state is reset before the clock starts, so the first strip's bind
  // counts. `state_changes` (optional) receives the glBindTexture calls of each object drawn.
  DrawTime time_draw(const std::vector<int>& objects, bool with_clear,
                     std::vector<int64_t>* state_changes = nullptr);

  // GL_SAMPLES_PASSED of `object` drawn alone, depth test off (untimed; see above).
  int64_t pixels_alone(int object);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ra::timing
