// Finding lit pixels in a read-back row of RGBA8 pixels (little-endian: R in the low byte), the
// inner loop of every readback (readback_measurement.cpp). A pixel is lit when its RGB bytes are not all
// zero (`any_colour`) or equal `colour` (the colour a primitive was drawn in); alpha is ignored.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/pixel_region.h"
#include "geometry/pixel_set.h"

namespace ra::platforms {

constexpr uint32_t kRgbMask = 0x00ffffffu;  // the RGB bytes of a pixel

// The first x in [x, w) whose pixel is lit when `lit_now` is false (dark when it is true), or w.
// The widest variant this CPU runs (AVX2: 32 pixels a step, else SSE2: 16), chosen once.
int next_change(const uint32_t* row, int x, int w, bool any_colour, uint32_t colour, bool lit_now);

// The variants, each with the same answer (pixel_scan_test.cpp); next_change_avx2 only where
// scan_has_avx2().
int next_change_portable(const uint32_t* row, int x, int w, bool any_colour, uint32_t colour,
                         bool lit_now);
int next_change_sse2(const uint32_t* row, int x, int w, bool any_colour, uint32_t colour,
                     bool lit_now);
int next_change_avx2(const uint32_t* row, int x, int w, bool any_colour, uint32_t colour,
                     bool lit_now);
bool scan_has_avx2();

// Appends the lit pixels of read-back rectangle `r` (GL window coordinates, y up) to `lit` as
// runs, lowest row first. `pixels` holds r's rows `stride` pixels apart: the row of y = r.y0 first
// (glReadPixels' order), or with `top_down` the row of y = r.y1 - 1 first (a Vulkan framebuffer's
// order, whose y points down).
void scan_rect(const uint32_t* pixels, size_t stride, bool top_down, const geometry::PixelRect& r,
               bool any_colour, uint32_t colour, geometry::PixelSet& lit);

// Appends `runs` (of several rectangles side by side, whose rows interleave) to `lit` in (y, x)
// order; sorts `runs` when they are not in that order already.
void append_in_order(std::vector<geometry::PixelRun>& runs, geometry::PixelSet& lit);

// Multisample readback: the samples lit of a resolved pixel from its red value v, for white drawn
// on black with `samples` samples per pixel: k where v is within 1 of 255 k / samples, else 255
// (no such k: the caller stops with the value).
std::array<uint8_t, 256> samples_from_resolved(int samples);

// Test-only fault of the GL and Vulkan platforms: the pixel a faulty driver lights outside the
// primitive's region, in the quadrant opposite the region's centre (window pixels, origin at the
// window's bottom left).
geometry::Pixel opposite_quadrant_pixel(const geometry::PixelRegion& region, int width, int height);

}  // namespace ra::platforms
