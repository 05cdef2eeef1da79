// The lit-pixel scan on the device (platforms/lit_mask.h): rectangles of RGBA8 pixels copied from
// the window become bit masks, one bit per pixel, and a count per rectangle, so that only these
// cross the bus. One invocation per 32-bit mask word: bit b of word k of a rectangle is the pixel
// in column 32 (k % words_per_row) + b of its row k / words_per_row (rows in the order they were
// copied), set when the pixel's RGB bytes equal the rectangle's colour (0xffffffff: any colour but
// black); alpha is ignored. Compiled to SPIR-V for Vulkan (VULKAN defined); GL compiles the text
// (as GLSL 4.30 where the context is older than 4.5).
#version 450
layout(local_size_x = 64) in;

struct Rect {
  uint first_pixel;    // where its rows start in `pixels`, row after row, `width` pixels each
  uint width, height;  // pixels
  uint colour;         // 0xBBGGRR (R in the low byte), or 0xffffffff: any but black
  uint first_word;     // where its mask starts in `words`, after the counts
  uint words_per_row;  // (width + 31) / 32
  uint pad0, pad1;
};

#ifdef VULKAN
layout(std430, set = 0, binding = 0) readonly buffer Pixels { uint pixels[]; };
layout(std430, set = 0, binding = 1) readonly buffer Rects { Rect rects[]; };
// counts[rect_count] (zeroed before the pass), then every rectangle's mask
layout(std430, set = 0, binding = 2) buffer Words { uint words[]; };
layout(push_constant) uniform Sizes { uint rect_count; uint word_count; uint word_base; };
#else
layout(std430, binding = 0) readonly buffer Pixels { uint pixels[]; };
layout(std430, binding = 1) readonly buffer Rects { Rect rects[]; };
layout(std430, binding = 2) buffer Words { uint words[]; };
uniform uint rect_count;
uniform uint word_count;
uniform uint word_base;  // of this dispatch: one holds at most 65,535 groups
#endif

void main() {
  uint g = word_base + gl_GlobalInvocationID.x;  // the mask word, over all rectangles
  if (g >= word_count) return;
  uint lo = 0, hi = rect_count - 1;  // the last rectangle whose mask starts at or before g
  while (lo < hi) {
    uint mid = (lo + hi + 1) / 2;
    if (rects[mid].first_word <= g) lo = mid;
    else hi = mid - 1;
  }
  Rect r = rects[lo];
  uint k = g - r.first_word;
  uint row = k / r.words_per_row, x0 = 32u * (k % r.words_per_row);
  uint first = r.first_pixel + row * r.width + x0;
  uint n = min(32u, r.width - x0);
  uint word = 0;
  for (uint b = 0; b < n; ++b) {
    uint rgb = pixels[first + b] & 0x00ffffffu;
    if (r.colour == 0xffffffffu ? rgb != 0u : rgb == r.colour) word |= 1u << b;
  }
  words[rect_count + g] = word;
  if (word != 0u) atomicAdd(words[lo], uint(bitCount(word)));
}
