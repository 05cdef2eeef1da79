// The lit-pixel scan on the device: a compute pass (platforms/shaders/lit_mask.comp) turns
// rectangles of the window into bit masks, one bit per pixel, and a count of lit pixels per
// rectangle, so that 1/32 of the pixels' bytes cross the bus. This file holds what the host shares
// with that pass: where each rectangle's pixels and mask words lie, and the decoding of a mask
// into pixel runs. The devices that run it: vulkan_device.cpp (VulkanLitMask).
//
// Coordinates: GL window coordinates, pixels, origin at the window's bottom-left corner, y up.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/pixel_region.h"
#include "geometry/pixel_set.h"

namespace ra::platforms {

// One rectangle as the compute pass reads it (std430: eight 32-bit words, the shader's `Rect`).
struct LitMaskRect {
  uint32_t first_pixel = 0;    // where its rows start in the copied pixels, `width` pixels each
  uint32_t width = 0, height = 0;
  uint32_t colour = 0;         // 0xBBGGRR, or kAnyColour (raster_device.h): any but black
  uint32_t first_word = 0;     // where its mask starts among all rectangles' mask words
  uint32_t words_per_row = 0;  // (width + 31) / 32
  uint32_t pad0 = 0, pad1 = 0;
};
static_assert(sizeof(LitMaskRect) == 32, "the shader's std430 Rect");

struct LitMaskLayout {
  std::vector<LitMaskRect> rects;
  uint64_t pixel_count = 0;  // of all rectangles, copied one after another
  uint64_t word_count = 0;   // of all masks
};

// Rectangle i (non-empty) scanned for colours[i]: pixels and masks packed in order.
LitMaskLayout lay_out_lit_masks(const std::vector<geometry::PixelRect>& rects,
                                const std::vector<uint32_t>& colours);

// Appends the lit pixels of rectangle `r` to `lit` as runs, lowest row first, from its mask: rows
// words_per_row words apart, bit b of word k of a row the pixel x = r.x0 + 32 k + b; the row of
// y = r.y0 first, or with `top_down` the row of y = r.y1 - 1 first (as the pixels were copied).
void append_mask_runs(const uint32_t* mask, uint32_t words_per_row, bool top_down,
                      const geometry::PixelRect& r, geometry::PixelSet& lit);

}  // namespace ra::platforms
