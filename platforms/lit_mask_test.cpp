// The host's side of the scan on the device (lit_mask.h): masks decode to the pixel runs that the
// host scan (pixel_scan.h scan_rect) finds in the same pixels, for widths around every word
// boundary, both row orders, and runs that cross words; the layout packs rectangles in order.
#include "platforms/lit_mask.h"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <vector>

#include "platforms/pixel_scan.h"
#include "platforms/raster_device.h"

namespace ra::platforms {
namespace {

// The mask of `pixels` (rows of width w, in their stored order) for `colour`, bit by bit.
std::vector<uint32_t> brute_force_mask(const std::vector<uint32_t>& pixels, int w, int h,
                                       uint32_t colour) {
  const int words = (w + 31) / 32;
  std::vector<uint32_t> mask(size_t(words) * size_t(h), 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const uint32_t rgb = pixels[size_t(y) * w + x] & kRgbMask;
      if (colour == kAnyColour ? rgb != 0 : rgb == colour)
        mask[size_t(y) * words + x / 32] |= uint32_t(1) << (x % 32);
    }
  return mask;
}

TEST(LitMask, DecodesToTheHostScansRuns) {
  std::mt19937 rng(17);
  const uint32_t colour = 0x00a0b0c0u;
  int checked = 0;
  for (int w : {1, 2, 31, 32, 33, 63, 64, 65, 96, 100, 129}) {
    for (int pattern = 0; pattern < 5; ++pattern) {
      const int h = 1 + int(rng() % 5);
      std::vector<uint32_t> pixels(size_t(w) * h);
      for (uint32_t& p : pixels) {
        const uint32_t alpha = (rng() & 0xffu) << 24;  // ignored by both scans
        switch (pattern) {
          case 0: p = alpha; break;                                          // none lit
          case 1: p = alpha | colour; break;                                 // every pixel
          case 2: p = alpha | (rng() % 5 == 0 ? colour : 0); break;          // sparse
          case 3: p = alpha | (rng() % 6 ? colour : colour ^ 0x10000u); break;  // long runs
          default: p = rng(); break;                                         // any colour
        }
      }
      const geometry::PixelRect r{-7 + int(rng() % 20), 3 + int(rng() % 9), 0, 0};
      const geometry::PixelRect rect{r.x0, r.y0, r.x0 + w, r.y0 + h};
      for (const uint32_t c : {colour, kAnyColour})
        for (const bool top_down : {false, true}) {
          geometry::PixelSet from_pixels, from_mask;
          scan_rect(pixels.data(), size_t(w), top_down, rect, c == kAnyColour, c, from_pixels);
          const std::vector<uint32_t> mask = brute_force_mask(pixels, w, h, c);
          append_mask_runs(mask.data(), uint32_t(w + 31) / 32, top_down, rect, from_mask);
          ASSERT_EQ(from_mask, from_pixels) << "w " << w << " pattern " << pattern;
          ++checked;
        }
    }
  }
  EXPECT_EQ(checked, 11 * 5 * 4);
}

// A run over a word's last bit and the next word's first is one run, not two.
TEST(LitMask, RunsAcrossWordsJoin) {
  const uint32_t mask[3] = {0xc0000000u, 0xffffffffu, 0x00000001u};  // x = 30..64
  geometry::PixelSet lit;
  append_mask_runs(mask, 3, false, geometry::PixelRect{100, 5, 180, 6}, lit);
  ASSERT_EQ(lit.runs().size(), 1u);
  EXPECT_EQ(lit.runs()[0], (geometry::PixelRun{5, 130, 165}));
}

TEST(LitMask, LayoutPacksRectanglesInOrder) {
  const LitMaskLayout l = lay_out_lit_masks(
      {{0, 0, 33, 2}, {10, 10, 11, 11}, {0, 0, 64, 3}}, {1, kAnyColour, 7});
  ASSERT_EQ(l.rects.size(), 3u);
  EXPECT_EQ(l.rects[0].words_per_row, 2u);
  EXPECT_EQ(l.rects[1].first_pixel, 66u);
  EXPECT_EQ(l.rects[1].first_word, 4u);
  EXPECT_EQ(l.rects[1].colour, kAnyColour);
  EXPECT_EQ(l.rects[2].first_pixel, 67u);
  EXPECT_EQ(l.rects[2].first_word, 5u);
  EXPECT_EQ(l.pixel_count, 67u + 192u);
  EXPECT_EQ(l.word_count, 5u + 6u);
  EXPECT_THROW(lay_out_lit_masks({{0, 0, 0, 5}}, {1}), std::logic_error);
  EXPECT_THROW(lay_out_lit_masks({{0, 0, 1, 1}}, {}), std::logic_error);
}

}  // namespace
}  // namespace ra::platforms
