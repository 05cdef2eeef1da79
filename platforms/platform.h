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
  // The measurement's choices (readback_measurement.cpp): the clock render_us reads ("host" or
  // "device"), and whether overlapping primitives share a batch in layers of the window.
  std::string clock = "host";
  bool layered = false;
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
  // The drawing's time in microseconds, on the clock `device_clock` names. The host's clock: CPU
  // wall time of draw + glFinish (Vulkan: record, submit, fence wait); for a batch drawn under one
  // wait, the batch's time divided equally among its `batch_size` primitives; multisample
  // platforms: draw + resolve of the expected region + the wait. The device's clock: its
  // timestamps around this primitive's draw alone.
  double render_us = 0;
  double host_us = 0;         // the host's clock, always: this primitive's share of the wait
  bool device_clock = false;  // render_us is the device's time (else host_us)
  int batch_size = 1;
  bool full_scan = false;   // the whole window was inspected (no proof for a partial readback)
};

// Where a GL or Vulkan platform's time went since it was made: host microseconds summed over
// every call (benchmarks: bench/layered_bench.cpp).
struct StageTimes {
  double draw_us = 0;       // drawing: recording, submission and the wait for the device
  double device_us = 0;     // of which the device's timestamps saw (draws timed by the device)
  double transfer_us = 0;   // copies of regions to the host, or the scan on the device, and waits
  double host_scan_us = 0;  // finding lit pixels in what came back (pixels, or the device's bits)
  double results_us = 0;    // fetching occlusion counts and timestamps from the device
  double clear_us = 0;      // clearing the window (views, redraws, a spent colour counter)
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
  // `layers` (empty: every primitive in layer 0, their regions pairwise disjoint): the layer of
  // each primitive, below batch_layers(), as platforms/layer_packing.h packs them.
  virtual std::vector<RenderResult> render_batch(
      const std::vector<geometry::Primitive>& prims,
      const std::vector<geometry::PixelRegion>& expected, const std::vector<int>& layers = {}) {
    (void)layers;
    std::vector<RenderResult> out;
    out.reserve(prims.size());
    for (size_t i = 0; i < prims.size(); ++i) out.push_back(render(prims[i], expected[i]));
    return out;
  }
  // How many layers a batch may use in the current view (1: overlapping primitives are never
  // drawn in one batch).
  virtual int batch_layers() const { return 1; }
  // Zero where the platform does not keep them (the reference and test platforms).
  virtual StageTimes stage_times() const { return {}; }
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
// How a GL or Vulkan platform batches and times; the defaults are what `run` does.
struct BatchOptions {
  // Layers of the window (platforms/raster_device.h create_gl_device): 0 as the device decides
  // (layers where the device's clock times each primitive), 1 none (overlapping primitives drawn
  // one at a time), N at most N.
  int max_layers = 0;
  // Which clock render_us reads: kAuto the device's where it times the drawing itself
  // (RasterDevice::device_clock), else the host's; kDevice forces the device's timer (tests: it
  // must have one).
  enum class Clock { kAuto, kHost, kDevice };
  Clock clock = Clock::kAuto;
  // Where the lit pixels of an aliased window are found: kHost over the pixels read back (what
  // `run` does), kDevice by a compute pass that sends only a bit per pixel and a count per region
  // (RasterDevice::scans; platforms/lit_mask.h): benchmarks and tests, the device must have it.
  enum class Scan { kHost, kDevice };
  Scan scan = Scan::kHost;
};

// `wild_pixel_indices` (tests only): for these primitive indices GL also lights one pixel far from
// the primitive, inside the same occlusion query, as a driver bug would; the readback must find it.
std::unique_ptr<Platform> create_gl_platform(
    const rundir::PlatformSpec& spec, ReadbackMethod method = ReadbackMethod::kRegionWithProof,
    std::vector<uint64_t> wild_pixel_indices = {}, const BatchOptions& batching = {});
// A Vulkan platform (spec.draws_with_vulkan(); vulkan_device.cpp): the same readback methods
// and test faults as create_gl_platform.
std::unique_ptr<Platform> create_vulkan_platform(
    const rundir::PlatformSpec& spec, ReadbackMethod method = ReadbackMethod::kRegionWithProof,
    std::vector<uint64_t> wild_pixel_indices = {}, const BatchOptions& batching = {});
std::unique_ptr<Platform> create_reference_platform();
std::unique_ptr<Platform> create_faulty_platform(const rundir::FaultPlan& faults);

}  // namespace ra::platforms
