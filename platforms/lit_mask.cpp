// The host's side of the lit-pixel scan on the device (see the header).
#include "platforms/lit_mask.h"

#include <stdexcept>

namespace ra::platforms {

LitMaskLayout lay_out_lit_masks(const std::vector<geometry::PixelRect>& rects,
                                const std::vector<uint32_t>& colours) {
  if (rects.size() != colours.size())
    throw std::logic_error("lay_out_lit_masks: a colour per rectangle");
  LitMaskLayout out;
  for (size_t i = 0; i < rects.size(); ++i) {
    const geometry::PixelRect& r = rects[i];
    if (r.empty()) throw std::logic_error("lay_out_lit_masks: an empty rectangle");
    LitMaskRect m;
    m.first_pixel = uint32_t(out.pixel_count);
    m.width = uint32_t(r.x1 - r.x0);
    m.height = uint32_t(r.y1 - r.y0);
    m.colour = colours[i];
    m.first_word = uint32_t(out.word_count);
    m.words_per_row = (m.width + 31) / 32;
    out.pixel_count += uint64_t(m.width) * m.height;
    out.word_count += uint64_t(m.words_per_row) * m.height;
    if (out.pixel_count > UINT32_MAX || out.word_count > UINT32_MAX)
      throw std::logic_error("lay_out_lit_masks: more than 2^32 pixels in one scan");
    out.rects.push_back(m);
  }
  return out;
}

void append_mask_runs(const uint32_t* mask, uint32_t words_per_row, bool top_down,
                      const geometry::PixelRect& r, geometry::PixelSet& lit) {
  const int h = r.y1 - r.y0;
  for (int y = 0; y < h; ++y) {
    const uint32_t* row = mask + size_t(top_down ? h - 1 - y : y) * words_per_row;
    for (uint32_t k = 0; k < words_per_row; ++k) {
      uint32_t word = row[k];
      while (word != 0) {  // each run of set bits; runs that go on in the next word are joined
        const int begin = __builtin_ctz(word);
        const uint32_t from_begin = word >> begin;
        const int length = from_begin == UINT32_MAX ? 32 - begin : __builtin_ctz(~from_begin);
        const int x = r.x0 + int(32 * k) + begin;
        lit.append_run(r.y0 + y, x, x + length);
        word = length + begin >= 32 ? 0 : word & ~((uint32_t(1) << (begin + length)) - 1);
      }
    }
  }
}

}  // namespace ra::platforms
