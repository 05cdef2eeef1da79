// What the readback measurement (platforms/readback_measurement.cpp) needs of a driver: one RGBA8
// window it draws primitives into, an occlusion count, a readback of rectangles and, on the
// multisample platforms, a resolve. GL (gl_device.cpp) and Vulkan (vulkan_device.cpp) implement it
// with their own API calls; everything that decides what a primitive lit lives in the measurement.
//
// Coordinates: GL window coordinates, pixels, origin at the window's bottom-left corner, y up; a
// pixel (x, y) covers [x, x+1] x [y, y+1]. Colours: 0xBBGGRR, alpha always opaque.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "geometry/pixel_region.h"
#include "geometry/primitive.h"
#include "geometry/view.h"
#include "platforms/platform.h"

namespace ra::platforms {

constexpr uint32_t kWhite = 0x00ffffffu;  // the colour of full coverage (and the last of the counter)
constexpr uint32_t kAnyColour = 0xffffffffu;  // scan for any pixel that is not black

class RasterDevice {
 public:
  virtual ~RasterDevice() = default;
  // What the driver says about itself; timer_over_cpu stays NaN (the measurement fills it).
  virtual DriverInfo info() const = 0;
  // Makes this device the target of the calls that follow (GL: its context current on this
  // thread; several platforms may share a process in tests).
  virtual void bind() {}
  // Sizes the window to the view (a new window's contents are undefined), loads its projection and
  // modelview, and on first use draws a few primitives untimed so that the driver's first-draw
  // compilation does not land in a measured primitive. The caller clears afterwards.
  virtual void set_view(const geometry::View& view) = 0;
  virtual int width() const = 0;
  virtual int height() const = 0;
  // Draws prims[i] in colours[i], in order, as one submission that the CPU waits for, and returns
  // that CPU time in microseconds. `counted`: an occlusion query spans the draws (fragments, or
  // samples on a multisample window; read with counted_fragments()). `wild` (tests only): one more
  // point lighting that pixel, in colours.front(), inside the query. `resolve` (multisample only):
  // these rectangles are resolved inside the timed submission.
  virtual double draw(const std::vector<geometry::Primitive>& prims,
                      const std::vector<uint32_t>& colours, bool counted,
                      const geometry::Pixel* wild,
                      const std::vector<geometry::PixelRect>* resolve = nullptr) = 0;
  // Fragments (samples) that passed during the last counted draw.
  virtual uint64_t counted_fragments() = 0;

  // --- layered drawing: primitives that cannot overwrite each other, many per submission -------
  // The window has layers() colour images of its size (at least 1; draw(), resolve() and clear()
  // use layer 0, clear() clears them all). Each primitive of draw_each() goes into its own layer
  // (or shares one with primitives whose pixels it cannot reach), so overlapping lines and
  // triangles are drawn in one submission with one wait.
  virtual int layers() const = 0;
  // Draws prims[i] in colours[i] into layer layers[i], in order, as one submission that the CPU
  // waits for, each primitive inside its own occlusion query and, with `timed`, between two of the
  // device's timestamps; returns the CPU time of it all in microseconds. Aliased windows only.
  virtual double draw_each(const std::vector<geometry::Primitive>& prims,
                           const std::vector<uint32_t>& colours, const std::vector<int>& layers,
                           bool timed) = 0;
  // Of primitive i of the last draw_each(): the fragments that passed, and the device's time
  // between its timestamps in microseconds (NaN when it was not timed).
  virtual uint64_t fragments_of(size_t i) = 0;
  virtual double device_us_of(size_t i) = 0;
  // True where the device's clock times the drawing itself: a timer query, on a device that is
  // not the host's CPU (Mesa's llvmpipe, softpipe and lavapipe draw on the CPU; their timers see
  // part of their work: llvmpipe's 0.07 of it, docs/records.md).
  virtual bool device_clock() const = 0;
  // Resolves these rectangles of the multisample window into the single-sample one, untimed.
  virtual void resolve(const std::vector<geometry::PixelRect>& rects) = 0;
  // Copies these rectangles (inside the window) of the single-sample window to host memory, rect i
  // from layer layers[i] (all from layer 0 when `layers` is empty).
  // pixels(i) is rectangle i's first row, its rows r.x1 - r.x0 pixels apart: the row of y = r.y0
  // first, or with rows_top_down() the row of y = r.y1 - 1 first. Valid until the next call.
  virtual void read(const std::vector<geometry::PixelRect>& rects,
                    const std::vector<int>& layers = {}) = 0;
  virtual const uint32_t* pixels(size_t i) const = 0;
  virtual bool rows_top_down() const = 0;

  // --- the lit-pixel scan on the device (platforms/lit_mask.h) -------------------------------
  // True where the device can find lit pixels itself: a compute pass, so that only a bit per
  // pixel and a count per rectangle cross the bus.
  virtual bool scans() const { return false; }
  // As read(), but the device compares: bit (x, y) of rectangle i's mask is set when that pixel's
  // RGB equal colours[i] (kAnyColour: any colour but black). mask(i) holds rectangle i's rows,
  // (width + 31) / 32 words apart, in pixels()'s row order; lit_count(i) its bits set. Valid
  // until the next call.
  virtual void scan(const std::vector<geometry::PixelRect>& rects, const std::vector<int>& layers,
                    const std::vector<uint32_t>& colours);
  virtual const uint32_t* mask(size_t i) const;
  virtual uint64_t lit_count(size_t i) const;
  // Clears the whole window (every sample) to black and waits.
  virtual void clear() = 0;
  // The most primitives one draw() takes.
  virtual size_t max_batch() const = 0;
  // The device's timer against the CPU clock over the same draws (DriverInfo::timer_over_cpu), or
  // NaN without a timer. May leave another window size and view: set_view() sets them again.
  virtual double timer_over_cpu() = 0;
};

// How many layers a device gives a window of w x h pixels: as many as kLayerBudgetBytes of RGBA8
// hold, at most kMaxLayers (a 907 x 907 view: 40; 128 x 128: 64), at least 1. `max_layers` > 0
// caps it (tests, benchmarks; 1 turns layered drawing off).
constexpr size_t kLayerBudgetBytes = size_t(128) << 20;
constexpr int kMaxLayers = 64;
int layers_for_window(int w, int h, int max_layers);

// The devices. Both throw ra::util::UserError naming the platform when the driver cannot serve it.
// `max_layers` 0 (what `run` uses): layers_for_window's layers on a device with device_clock(),
// one elsewhere. On the CPU drivers a batch's shared wait would replace each line's and
// triangle's own time, and llvmpipe gains nothing: it rasterizes its scene at every change of
// framebuffer (docs/benchmarks.md). Else as layers_for_window's.
std::unique_ptr<RasterDevice> create_gl_device(const rundir::PlatformSpec& spec, int max_layers = 0);
std::unique_ptr<RasterDevice> create_vulkan_device(const rundir::PlatformSpec& spec,
                                                   int max_layers = 0);

}  // namespace ra::platforms
