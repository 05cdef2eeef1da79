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
  // Resolves these rectangles of the multisample window into the single-sample one, untimed.
  virtual void resolve(const std::vector<geometry::PixelRect>& rects) = 0;
  // Copies these rectangles (inside the window) of the single-sample window to host memory.
  // pixels(i) is rectangle i's first row, its rows r.x1 - r.x0 pixels apart: the row of y = r.y0
  // first, or with rows_top_down() the row of y = r.y1 - 1 first. Valid until the next call.
  virtual void read(const std::vector<geometry::PixelRect>& rects) = 0;
  virtual const uint32_t* pixels(size_t i) const = 0;
  virtual bool rows_top_down() const = 0;
  // Clears the whole window (every sample) to black and waits.
  virtual void clear() = 0;
  // The most primitives one draw() takes.
  virtual size_t max_batch() const = 0;
  // The device's timer against the CPU clock over the same draws (DriverInfo::timer_over_cpu), or
  // NaN without a timer. May leave another window size and view: set_view() sets them again.
  virtual double timer_over_cpu() = 0;
};

// The devices. Both throw ra::util::UserError naming the platform when the driver cannot serve it.
std::unique_ptr<RasterDevice> create_gl_device(const rundir::PlatformSpec& spec);
std::unique_ptr<RasterDevice> create_vulkan_device(const rundir::PlatformSpec& spec);

}  // namespace ra::platforms
