// Sets of lit pixels in GL window coordinates: pixel (x, y) covers [x, x+1) x [y, y+1), centre at
// (x + 0.5, y + 0.5); y = 0 is the bottom row (glReadPixels order).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

namespace ra {

struct Pixel {
  int32_t x = 0, y = 0;
  friend bool operator==(Pixel a, Pixel b) { return a.x == b.x && a.y == b.y; }
  friend bool operator<(Pixel a, Pixel b) { return a.y != b.y ? a.y < b.y : a.x < b.x; }
};

// Sorted by (y, x), no duplicates.
using PixelSet = std::vector<Pixel>;

inline void normalize(PixelSet& s) {
  std::sort(s.begin(), s.end());
  s.erase(std::unique(s.begin(), s.end()), s.end());
}

// Size of the symmetric difference of two sorted sets: 0 when they are equal.
inline int64_t symmetric_difference_size(const PixelSet& a, const PixelSet& b) {
  int64_t diff = 0;
  size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (a[i] == b[j]) {
      ++i, ++j;
    } else if (a[i] < b[j]) {
      ++diff, ++i;
    } else {
      ++diff, ++j;
    }
  }
  return diff + static_cast<int64_t>(a.size() - i) + static_cast<int64_t>(b.size() - j);
}

// FNV-1a over the sorted coordinates: lets two runs compare pixel sets exactly from records alone.
inline uint64_t pixel_set_hash(const PixelSet& s) {
  uint64_t h = 0xcbf29ce484222325ull;
  auto mix = [&h](uint32_t v) {
    for (int k = 0; k < 4; ++k) {
      h ^= (v >> (8 * k)) & 0xffu;
      h *= 0x100000001b3ull;
    }
  };
  for (const Pixel& p : s) {
    mix(static_cast<uint32_t>(p.x));
    mix(static_cast<uint32_t>(p.y));
  }
  return h;
}

// Integer rectangle [x0, x1) x [y0, y1) in window pixels.
struct PixelRect {
  int32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  int64_t area() const { return empty() ? 0 : int64_t(x1 - x0) * (y1 - y0); }
};

}  // namespace ra
