// Platforms: the renderers the runner draws through. A worker process serves exactly one platform
// (Mesa picks its driver from the environment when the first context is made).
#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "geometry/pixel_region.h"
#include "geometry/pixel_set.h"
#include "geometry/primitive.h"
#include "geometry/view.h"
#include "rundir/fault_plan.h"
#include "rundir/platform_spec.h"

namespace ra::platforms {

// What a driver says about itself (glGetString and a few capabilities).
struct DriverInfo {
  std::string renderer, version, vendor;
  int subpixel_bits = 0;        // GL_SUBPIXEL_BITS; 0 for exact rasterizers
  bool timer_query = false;     // GL_ARB_timer_query
  int max_samples = 0;          // GL_MAX_SAMPLES (0 for the non-GL platforms)
  std::string backend;          // GlContext::backend(): how the context was made
  // GL_TIME_ELAPSED / CPU wall time over the same draws (RasterDevice::timer_over_cpu): near 1 where the
  // driver's timer measures what the CPU waits for; NaN without a timer query.
  double timer_over_cpu = std::numeric_limits<double>::quiet_NaN();
  // Vulkan platforms only (platforms/vulkan_context.h): lineSubPixelPrecisionBits, strictLines,
  // the modes of VK_EXT_line_rasterization ("rectangular, bresenham, smooth"; "default" without
  // it), the line mode the platform draws with ("default", "bresenham"). Empty line_modes: GL.
  int line_subpixel_bits = 0;
  bool strict_lines = false;
  std::string line_modes = "", line_mode = "";
};

// One primitive as rendered.
struct RenderResult {
  geometry::PixelSet lit;  // every lit pixel (any coverage), GL window coordinates
  // Multisample platforms only (`samples` > 0): samples_lit[i] = samples of the i-th pixel of
  // `lit`, in its (y, x) iteration order, that the primitive covered, 1..samples; the pixel's
  // coverage is samples_lit[i] / samples. Aliased platforms: samples = 0, samples_lit empty (each
  // lit pixel is wholly lit).
  int samples = 0;
  std::vector<uint8_t> samples_lit;
  // CPU wall time of draw + glFinish, microseconds; for a batch drawn under one glFinish, the
  // batch's time divided equally among its `batch_size` primitives. Multisample platforms: draw +
  // resolve of the expected region (glBlitFramebuffer) + glFinish.
  double render_us = 0;
  int batch_size = 1;
  bool full_scan = false;   // the whole window was inspected (no proof for a partial readback)
};

class Platform {
 public:
  virtual ~Platform() = default;
  virtual DriverInfo driver_info() const = 0;
  // Measures DriverInfo::timer_over_cpu (a few hundred milliseconds on softpipe), stores it in
  // what driver_info() returns from now on, and returns it; NaN where there is no timer. Asked
  // once per run, by the worker that writes the run's driver file, not by every worker.
  virtual double measure_timer_over_cpu() { return std::numeric_limits<double>::quiet_NaN(); }
  // Makes `view` current: window size, projection and modelview matrices.
  virtual void set_view(const geometry::View& view) = 0;
  // Draws `prim` alone, white on black, width/size 1, no antialiasing (multisampling on the
  // multisample platforms), both faces filled, and returns every pixel it lit. `expected` is the window region where the ideal primitive lies
  // (its clipped bounding box, or a strip along a line, plus a margin; possibly empty): an
  // implementation may read back only that region when it proves that nothing was lit outside it.
  virtual RenderResult render(const geometry::Primitive& prim,
                              const geometry::PixelRegion& expected) = 0;
  // Draws each primitive as render() would, in order, and returns their results. An
  // implementation may share one completeness proof among the batch (readback_measurement.cpp); this
  // default draws them one by one.
  virtual std::vector<RenderResult> render_batch(
      const std::vector<geometry::Primitive>& prims,
      const std::vector<geometry::PixelRegion>& expected) {
    std::vector<RenderResult> out;
    out.reserve(prims.size());
    for (size_t i = 0; i < prims.size(); ++i) out.push_back(render(prims[i], expected[i]));
    return out;
  }
};

// Creates the platform for this process. GL platforms make their context with
// create_gl_context (platforms/gl_context.h), which sets Mesa's environment (and LP_NUM_THREADS=0
// unless the user set it: thread hand-off dominates one-primitive frames).
// `spec` comes from find_platform, or from experiment_platform for a driver build an experiment
// declares.
std::unique_ptr<Platform> create_platform(const rundir::PlatformSpec& spec, const rundir::FaultPlan& faults);

// How a GL or Vulkan platform finds the lit pixels. Only kRegionWithProof is used by `run`; the others
// exist for the benchmark (`make bench`), which compares them side by side.
enum class ReadbackMethod {
  kRegionWithProof,  // read the expected region; an occlusion query proves nothing lit elsewhere
  kFullWindow,       // clear and read back the whole window for every primitive (the paper's way)
  kDrawOnly,         // draw + glFinish, nothing read: the floor (RenderResult::lit stays empty)
};
// `wild_pixel_indices` (tests only): for these primitive indices GL also lights one pixel far from
// the primitive, inside the same occlusion query, as a driver bug would; the readback must find it.
std::unique_ptr<Platform> create_gl_platform(
    const rundir::PlatformSpec& spec, ReadbackMethod method = ReadbackMethod::kRegionWithProof,
    std::vector<uint64_t> wild_pixel_indices = {});
// A Vulkan platform (spec.draws_with_vulkan(); vulkan_device.cpp): the same readback methods
// and test faults as create_gl_platform.
std::unique_ptr<Platform> create_vulkan_platform(
    const rundir::PlatformSpec& spec, ReadbackMethod method = ReadbackMethod::kRegionWithProof,
    std::vector<uint64_t> wild_pixel_indices = {});
std::unique_ptr<Platform> create_reference_platform();
std::unique_ptr<Platform> create_faulty_platform(const rundir::FaultPlan& faults);

}  // namespace ra::platforms
