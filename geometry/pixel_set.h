// Sets of lit pixels in GL window coordinates: pixel (x, y) covers [x, x+1) x [y, y+1), centre at
// (x + 0.5, y + 0.5); y = 0 is the bottom row (glReadPixels order).
//
// Stored as maximal horizontal runs sorted by (y, x): a filled 907 x 907 triangle is ~900 runs,
// not ~400,000 pixels, so building, hashing and comparing sets costs O(rows), not O(area).
#pragma once

#include <cstdint>
#include <initializer_list>
#include <iterator>
#include <vector>

namespace ra::geometry {

struct Pixel {
  int32_t x = 0, y = 0;
  friend bool operator==(Pixel a, Pixel b) { return a.x == b.x && a.y == b.y; }
  friend bool operator!=(Pixel a, Pixel b) { return !(a == b); }
  friend bool operator<(Pixel a, Pixel b) { return a.y != b.y ? a.y < b.y : a.x < b.x; }
};

// A horizontal run of lit pixels: columns [x_begin, x_end) of row y.
struct PixelRun {
  int32_t y = 0, x_begin = 0, x_end = 0;
  int64_t length() const { return int64_t(x_end) - x_begin; }
  friend bool operator==(const PixelRun& a, const PixelRun& b) {
    return a.y == b.y && a.x_begin == b.x_begin && a.x_end == b.x_end;
  }
};

// Integer rectangle [x0, x1) x [y0, y1) in window pixels.
struct PixelRect {
  int32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  int64_t area() const { return empty() ? 0 : int64_t(x1 - x0) * (y1 - y0); }
};

class PixelSet {
 public:
  PixelSet() = default;
  // Any order, duplicates allowed.
  PixelSet(std::initializer_list<Pixel> pixels);
  static PixelSet from_pixels(std::vector<Pixel> pixels);

  // Appends columns [x_begin, x_end) of row y. Runs must come in (y, x) order without overlap
  // (x_begin >= the previous run's x_end on the same row); touching runs are merged. Empty runs
  // are ignored. Inline: the readback scan and the reference rasterizers call it per run or pixel.
  void append_run(int32_t y, int32_t x_begin, int32_t x_end) {
    if (x_end <= x_begin) return;
    if (!runs_.empty()) {
      PixelRun& last = runs_.back();
      if (y < last.y || (y == last.y && x_begin < last.x_end)) out_of_order();
      if (y == last.y && x_begin == last.x_end) {
        last.x_end = x_end;
        count_ += int64_t(x_end) - x_begin;
        return;
      }
    }
    runs_.push_back({y, x_begin, x_end});
    count_ += int64_t(x_end) - x_begin;
  }
  // Adds or removes one pixel anywhere: O(runs). For tests and fault injection, not hot paths.
  void insert(Pixel p);
  void erase(Pixel p);
  // Moves every pixel by (dx, dy).
  void translate(int32_t dx, int32_t dy);
  // Keeps only the pixels inside `r`.
  void clip_to(const PixelRect& r);

  const std::vector<PixelRun>& runs() const { return runs_; }
  int64_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  bool contains(Pixel p) const;
  Pixel front() const { return {runs_.front().x_begin, runs_.front().y}; }  // lowest (y, x)
  std::vector<Pixel> pixels() const;  // every pixel in (y, x) order: O(size)
  void clear() { runs_.clear(), count_ = 0; }

  friend bool operator==(const PixelSet& a, const PixelSet& b) { return a.runs_ == b.runs_; }
  friend bool operator!=(const PixelSet& a, const PixelSet& b) { return !(a == b); }

  // Pixels in (y, x) order.
  class const_iterator {
   public:
    using iterator_category = std::forward_iterator_tag;
    using value_type = Pixel;
    using difference_type = std::ptrdiff_t;
    using pointer = const Pixel*;
    using reference = Pixel;
    const_iterator(const PixelRun* run, const PixelRun* last, int32_t x)
        : run_(run), last_(last), x_(x) {}
    Pixel operator*() const { return {x_, run_->y}; }
    const_iterator& operator++() {
      if (++x_ == run_->x_end && ++run_ != last_) x_ = run_->x_begin;
      return *this;
    }
    // Past the last run, x_ is left as it was: compare runs first.
    friend bool operator==(const const_iterator& a, const const_iterator& b) {
      return a.run_ == b.run_ && (a.run_ == a.last_ || a.x_ == b.x_);
    }
    friend bool operator!=(const const_iterator& a, const const_iterator& b) { return !(a == b); }

   private:
    const PixelRun *run_, *last_;
    int32_t x_;
  };
  const_iterator begin() const {
    const PixelRun* first = runs_.data();
    return {first, first + runs_.size(), runs_.empty() ? 0 : first->x_begin};
  }
  const_iterator end() const {
    const PixelRun* last = runs_.data() + runs_.size();
    return {last, last, 0};
  }

 private:
  [[noreturn]] static void out_of_order();  // throws std::logic_error
  std::vector<PixelRun> runs_;  // maximal, sorted by (y, x_begin), disjoint and not touching
  int64_t count_ = 0;
};

// Size of the symmetric difference of two sets: 0 when they are equal. O(runs).
int64_t symmetric_difference_size(const PixelSet& a, const PixelSet& b);

// The pixels of `a` that are not in `b`. O(runs).
PixelSet set_difference(const PixelSet& a, const PixelSet& b);

// FNV-1a over the runs (y, x_begin, x_end as little-endian 32-bit words): lets two runs of the
// audit compare pixel sets exactly from their records alone.
uint64_t pixel_set_hash(const PixelSet& s);

}  // namespace ra::geometry
