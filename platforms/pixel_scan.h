// Finding lit pixels in a read-back row of RGBA8 pixels (little-endian: R in the low byte), the
// inner loop of every readback (gl_platform.cpp). A pixel is lit when its RGB bytes are not all
// zero (`any_colour`) or equal `colour` (the colour a primitive was drawn in); alpha is ignored.
#pragma once

#include <cstdint>

namespace ra {

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

}  // namespace ra
