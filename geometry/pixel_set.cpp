// Run-length pixel sets. See pixel_set.h.
#include "geometry/pixel_set.h"

#include <algorithm>
#include <stdexcept>

namespace ra::geometry {
namespace {

bool run_before(const PixelRun& a, const PixelRun& b) {
  return a.y != b.y ? a.y < b.y : a.x_begin < b.x_begin;
}

}  // namespace

PixelSet::PixelSet(std::initializer_list<Pixel> pixels)
    : PixelSet(from_pixels(std::vector<Pixel>(pixels))) {}

PixelSet PixelSet::from_pixels(std::vector<Pixel> pixels) {
  // Often in order already (a segment rasterized along y, or along x with a slope >= 0).
  if (!std::is_sorted(pixels.begin(), pixels.end())) std::sort(pixels.begin(), pixels.end());
  pixels.erase(std::unique(pixels.begin(), pixels.end()), pixels.end());
  PixelSet s;
  for (const Pixel& p : pixels) s.append_run(p.y, p.x, p.x + 1);
  return s;
}

void PixelSet::out_of_order() {
  throw std::logic_error("PixelSet::append_run: runs out of (y, x) order or overlapping");
}

bool PixelSet::contains(Pixel p) const {
  // First run not before (p.y, p.x + 1): the candidate is the one just before it.
  auto it = std::upper_bound(runs_.begin(), runs_.end(), PixelRun{p.y, p.x, p.x},
                             [](const PixelRun& key, const PixelRun& r) { return run_before(key, r); });
  if (it == runs_.begin()) return false;
  --it;
  return it->y == p.y && it->x_begin <= p.x && p.x < it->x_end;
}

void PixelSet::insert(Pixel p) {
  if (contains(p)) return;
  std::vector<Pixel> all = pixels();
  all.push_back(p);
  *this = from_pixels(std::move(all));
}

void PixelSet::erase(Pixel p) {
  if (!contains(p)) return;
  std::vector<Pixel> all = pixels();
  all.erase(std::find(all.begin(), all.end(), p));
  *this = from_pixels(std::move(all));
}

void PixelSet::translate(int32_t dx, int32_t dy) {
  for (PixelRun& r : runs_) r.y += dy, r.x_begin += dx, r.x_end += dx;
}

void PixelSet::clip_to(const PixelRect& rect) {
  PixelSet out;
  for (const PixelRun& r : runs_)
    if (r.y >= rect.y0 && r.y < rect.y1)
      out.append_run(r.y, std::max(r.x_begin, rect.x0), std::min(r.x_end, rect.x1));
  *this = std::move(out);
}

std::vector<Pixel> PixelSet::pixels() const {
  std::vector<Pixel> out;
  out.reserve(size_t(count_));
  for (const PixelRun& r : runs_)
    for (int32_t x = r.x_begin; x < r.x_end; ++x) out.push_back({x, r.y});
  return out;
}

int64_t symmetric_difference_size(const PixelSet& a, const PixelSet& b) {
  // |A xor B| = |A| + |B| - 2 |A and B|; the intersection by merging the sorted runs.
  const std::vector<PixelRun>& ra = a.runs();
  const std::vector<PixelRun>& rb = b.runs();
  int64_t common = 0;
  size_t i = 0, j = 0;
  while (i < ra.size() && j < rb.size()) {
    if (ra[i].y != rb[j].y) {
      ra[i].y < rb[j].y ? ++i : ++j;
      continue;
    }
    common += std::max<int64_t>(
        0, int64_t(std::min(ra[i].x_end, rb[j].x_end)) - std::max(ra[i].x_begin, rb[j].x_begin));
    ra[i].x_end < rb[j].x_end ? ++i : ++j;  // the run ending first overlaps nothing further
  }
  return a.size() + b.size() - 2 * common;
}

PixelSet set_difference(const PixelSet& a, const PixelSet& b) {
  PixelSet out;
  const std::vector<PixelRun>& rb = b.runs();
  size_t j = 0;  // first run of b that can still overlap a run of a (both sorted by (y, x))
  for (const PixelRun& r : a.runs()) {
    while (j < rb.size() && (rb[j].y < r.y || (rb[j].y == r.y && rb[j].x_end <= r.x_begin))) ++j;
    int32_t x = r.x_begin;
    for (size_t k = j; k < rb.size() && rb[k].y == r.y && rb[k].x_begin < r.x_end; ++k) {
      out.append_run(r.y, x, std::max(x, rb[k].x_begin));
      x = std::max(x, rb[k].x_end);
    }
    out.append_run(r.y, x, r.x_end);
  }
  return out;
}

uint64_t pixel_set_hash(const PixelSet& s) {
  constexpr uint64_t kPrime = 0x100000001b3ull, kPrime2 = kPrime * kPrime;  // mod 2^64
  uint64_t h = 0xcbf29ce484222325ull;
  auto mix = [&h](int32_t value) {
    const uint32_t v = uint32_t(value);
    h = (h ^ (v & 0xffu)) * kPrime;
    h = (h ^ ((v >> 8) & 0xffu)) * kPrime;
    // Two zero high bytes (every coordinate in [0, 65535]): x ^ 0 = x, so their two steps are one
    // multiplication by the prime squared; the same hash in three multiplications, not four.
    if (v >> 16 == 0) {
      h *= kPrime2;
    } else {
      h = (h ^ ((v >> 16) & 0xffu)) * kPrime;
      h = (h ^ (v >> 24)) * kPrime;
    }
  };
  for (const PixelRun& r : s.runs()) {
    mix(r.y);
    mix(r.x_begin);
    mix(r.x_end);
  }
  return h;
}

}  // namespace ra::geometry
