// The lit-pixel scan: its SSE2 and AVX2 variants give the portable loop's answer at every start,
// for rows of every length up to 100 (so every tail of the vector loops), alpha ignored.
#include "platforms/pixel_scan.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace ra::platforms {
namespace {

TEST(PixelScan, VectorVariantsEqualThePortableLoop) {
  std::mt19937 rng(9);
  const uint32_t colour = 0x00123456u;
  int checked = 0;
  for (int w = 0; w <= 100; ++w) {
    for (int pattern = 0; pattern < 8; ++pattern) {
      std::vector<uint32_t> row(size_t(w) + 1);  // one more: never read (w bounds the scan)
      for (uint32_t& p : row) {
        const uint32_t alpha = (rng() & 0xffu) << 24;  // ignored by the scan
        switch (pattern) {
          case 0: p = alpha; break;                                      // all dark
          case 1: p = alpha | colour; break;                             // all lit in colour
          case 2: p = alpha | (rng() % 4 == 0 ? colour : 0); break;      // sparse
          case 3: p = alpha | (rng() % 4 ? colour : 0); break;           // dense
          case 4: p = alpha | (rng() % 3 == 0 ? colour ^ 1u : colour); break;  // near colours
          case 5: p = rng(); break;                                      // anything
          case 6: p = alpha; break;                                      // dark, then see below
          default: p = alpha | colour; break;                            // lit, then see below
        }
      }
      // One pixel of the other kind at the end: from the starts x = 0..w - 1, the change falls on
      // every position of every vector step.
      if (w > 0 && pattern == 6) row[size_t(w) - 1] |= colour;
      if (w > 0 && pattern == 7) row[size_t(w) - 1] &= ~kRgbMask;
      row[size_t(w)] = colour;  // a sentinel that would be found if read
      for (int x = 0; x <= w; ++x)
        for (const bool any : {false, true})
          for (const bool lit_now : {false, true}) {
            const int want = next_change_portable(row.data(), x, w, any, colour, lit_now);
            ASSERT_EQ(next_change_sse2(row.data(), x, w, any, colour, lit_now), want)
                << "w " << w << " x " << x << " pattern " << pattern;
            if (scan_has_avx2()) {
              ASSERT_EQ(next_change_avx2(row.data(), x, w, any, colour, lit_now), want)
                  << "w " << w << " x " << x << " pattern " << pattern;
            }
            ASSERT_EQ(next_change(row.data(), x, w, any, colour, lit_now), want);
            ++checked;
          }
    }
  }
  EXPECT_EQ(checked, 8 * 4 * (101 * 102 / 2));
}

// Hand-made: runs found where they are, alpha never makes a pixel lit.
TEST(PixelScan, FindsRunsByHand) {
  std::vector<uint32_t> row(70, 0xff000000u);  // black, opaque
  for (int x = 33; x < 61; ++x) row[size_t(x)] = 0xff0000ffu;  // red
  EXPECT_EQ(next_change(row.data(), 0, 70, true, 0, false), 33);
  EXPECT_EQ(next_change(row.data(), 33, 70, true, 0, true), 61);
  EXPECT_EQ(next_change(row.data(), 61, 70, true, 0, false), 70);
  EXPECT_EQ(next_change(row.data(), 0, 70, false, 0x000000ffu, false), 33);
  EXPECT_EQ(next_change(row.data(), 0, 70, false, 0x0000ff00u, false), 70);  // no green pixel
}

}  // namespace
}  // namespace ra::platforms
