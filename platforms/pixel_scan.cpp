// Lit-pixel scan of read-back rows, three widths; see pixel_scan.h. The scan was a sixth of a large
// llvmpipe triangle's time with one pixel a step, 6-7% with SSE2's 16.
#include "platforms/pixel_scan.h"

#include <algorithm>
#include <cmath>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define RA_SCAN_X86 1
#endif

namespace ra::platforms {

int next_change_portable(const uint32_t* row, int x, int w, bool any_colour, uint32_t colour,
                         bool lit_now) {
  for (; x < w; ++x) {
    const uint32_t v = row[x] & kRgbMask;
    if ((any_colour ? v != 0 : v == colour) != lit_now) return x;
  }
  return w;
}

#if defined(RA_SCAN_X86)

int next_change_sse2(const uint32_t* row, int x, int w, bool any_colour, uint32_t colour,
                     bool lit_now) {
  const __m128i rgb = _mm_set1_epi32(int(kRgbMask));
  const __m128i target = _mm_set1_epi32(any_colour ? 0 : int(colour));
  // bit i set: pixel at + i equals the target (black, or `colour`)
  auto equal4 = [&](int at) {
    const __m128i v =
        _mm_and_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(row + at)), rgb);
    return unsigned(_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(v, target))));
  };
  const unsigned flip = (any_colour ? 1u : 0u) ^ (lit_now ? 1u : 0u);  // bits that mean "change"
  for (; x + 16 <= w; x += 16) {
    const unsigned equal =
        equal4(x) | equal4(x + 4) << 4 | equal4(x + 8) << 8 | equal4(x + 12) << 12;
    const unsigned change = flip ? ~equal & 0xffffu : equal;
    if (change) return x + __builtin_ctz(change);
  }
  for (; x + 4 <= w; x += 4) {
    const unsigned change = flip ? ~equal4(x) & 0xfu : equal4(x);
    if (change) return x + __builtin_ctz(change);
  }
  return next_change_portable(row, x, w, any_colour, colour, lit_now);
}

// bit i set: pixel p[i] equals the target (a lambda would not inherit the target attribute)
__attribute__((target("avx2"), always_inline)) static inline unsigned equal8(const uint32_t* p,
                                                                             __m256i rgb,
                                                                             __m256i target) {
  const __m256i v = _mm256_and_si256(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)), rgb);
  return unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(v, target))));
}

__attribute__((target("avx2"))) int next_change_avx2(const uint32_t* row, int x, int w,
                                                     bool any_colour, uint32_t colour,
                                                     bool lit_now) {
  const __m256i rgb = _mm256_set1_epi32(int(kRgbMask));
  const __m256i target = _mm256_set1_epi32(any_colour ? 0 : int(colour));
  const bool flip = any_colour != lit_now;  // then a change is a pixel not equal to the target
  for (; x + 32 <= w; x += 32) {
    const unsigned equal = equal8(row + x, rgb, target) | equal8(row + x + 8, rgb, target) << 8 |
                           equal8(row + x + 16, rgb, target) << 16 |
                           equal8(row + x + 24, rgb, target) << 24;
    const unsigned change = flip ? ~equal : equal;
    if (change) return x + __builtin_ctz(change);
  }
  for (; x + 8 <= w; x += 8) {
    const unsigned equal = equal8(row + x, rgb, target);
    const unsigned change = flip ? ~equal & 0xffu : equal;
    if (change) return x + __builtin_ctz(change);
  }
  return next_change_portable(row, x, w, any_colour, colour, lit_now);
}

bool scan_has_avx2() { return __builtin_cpu_supports("avx2"); }

#else  // not x86: the portable loop under every name

int next_change_sse2(const uint32_t* row, int x, int w, bool any_colour, uint32_t colour,
                     bool lit_now) {
  return next_change_portable(row, x, w, any_colour, colour, lit_now);
}
int next_change_avx2(const uint32_t* row, int x, int w, bool any_colour, uint32_t colour,
                     bool lit_now) {
  return next_change_portable(row, x, w, any_colour, colour, lit_now);
}
bool scan_has_avx2() { return false; }

#endif

int next_change(const uint32_t* row, int x, int w, bool any_colour, uint32_t colour,
                bool lit_now) {
  static const auto best = scan_has_avx2() ? next_change_avx2 : next_change_sse2;
  return best(row, x, w, any_colour, colour, lit_now);
}

void scan_rect(const uint32_t* pixels, size_t stride, bool top_down, const geometry::PixelRect& r,
               bool any_colour, uint32_t colour, geometry::PixelSet& lit) {
  const int w = r.x1 - r.x0, h = r.y1 - r.y0;
  for (int y = 0; y < h; ++y) {
    const uint32_t* row = pixels + size_t(top_down ? h - 1 - y : y) * stride;
    int x = 0;
    while (x < w) {
      const int begin = next_change(row, x, w, any_colour, colour, false);
      if (begin == w) break;
      x = next_change(row, begin, w, any_colour, colour, true);
      lit.append_run(r.y0 + y, r.x0 + begin, r.x0 + x);
    }
  }
}

void append_in_order(std::vector<geometry::PixelRun>& runs, geometry::PixelSet& lit) {
  const auto before = [](const geometry::PixelRun& a, const geometry::PixelRun& b) {
    return a.y != b.y ? a.y < b.y : a.x_begin < b.x_begin;
  };
  if (!std::is_sorted(runs.begin(), runs.end(), before))
    std::sort(runs.begin(), runs.end(), before);
  for (const geometry::PixelRun& run : runs) lit.append_run(run.y, run.x_begin, run.x_end);
}

std::array<uint8_t, 256> samples_from_resolved(int samples) {
  std::array<uint8_t, 256> decode{};
  for (int v = 0; v < 256; ++v) {
    const int k = int(std::lround(v * samples / 255.0));
    decode[v] = std::fabs(v - 255.0 * k / samples) <= 1.0 ? uint8_t(k) : uint8_t(255);
  }
  return decode;
}

geometry::Pixel opposite_quadrant_pixel(const geometry::PixelRegion& region, int width,
                                        int height) {
  const geometry::PixelRect expected = region.bounds();
  const int cx = expected.empty() ? 0 : (expected.x0 + expected.x1) / 2;
  const int cy = expected.empty() ? 0 : (expected.y0 + expected.y1) / 2;
  return {(cx + width / 2) % width, (cy + height / 2) % height};
}

}  // namespace ra::platforms
