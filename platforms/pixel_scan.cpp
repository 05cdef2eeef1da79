// Lit-pixel scan of read-back rows, three widths; see pixel_scan.h. The scan was a sixth of a large
// llvmpipe triangle's time with one pixel a step, 6-7% with SSE2's 16.
#include "platforms/pixel_scan.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define RA_SCAN_X86 1
#endif

namespace ra {

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

}  // namespace ra
