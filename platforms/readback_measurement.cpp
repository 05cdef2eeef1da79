// The measurement of every GL and Vulkan platform: what each primitive lit, found by reading back
// only the region where it should lie and proving that nothing was lit elsewhere. The driver is
// reached through a RasterDevice (platforms/raster_device.h); this file holds no API calls.
//
// Completeness of the readback: only the expected region is scanned, and an occlusion query
// counts the fragments the primitive produced. Without multisampling and with no depth or stencil
// test, every fragment of one point, line or polygon lights a distinct pixel, so when the count
// equals the number of lit pixels found in the region nothing was lit elsewhere; when it differs,
// the whole window is scanned (RenderResult::full_scan).
//
// No clear between primitives: each primitive is drawn in its own colour (a 24-bit counter) and its
// pixels are those holding exactly that colour. Coverage does not depend on the colour (it is a
// vertex attribute, not a rasterization parameter), and a scissored clear is a quad draw in Mesa:
// it cost 1.7x (llvmpipe) to 1.8x (softpipe) the drawing of a large 907x907 triangle. Should a
// driver not return the colour exactly, or leave pixels of another colour, the full scan still
// disagrees with the count and the primitive is drawn again the old way: whole window cleared,
// white, every non-black pixel taken.
//
// Batches: each primitive in its own colour, one occlusion query and one wait around them all (a
// wait per primitive cost more than a small primitive's drawing: llvmpipe walks all its tiles at
// every flush). The sum over the batch of the pixels found in each primitive's region with its
// colour equals the fragment count only when every fragment was found where it belongs and none
// was overwritten by another (each found pixel is a distinct fragment); any other outcome redraws
// the batch one primitive at a time, each with its own proof and time.
//
// Layered batches (lines and triangles that overlap, RasterDevice::draw_each): each primitive in
// its own colour, in the layer platforms/layer_packing.h gave it, inside its own occlusion query,
// the whole batch under one wait. Each primitive has its own proof: its pixels found in its
// region in its colour equal its fragment count (found pixels are distinct fragments of it, and
// a pixel another primitive of its layer overwrote, or one outside its region, leaves the count
// higher). A primitive without proof is looked for in its whole layer, then drawn again alone,
// white, on a cleared window, as a primitive drawn alone is; the others keep their batch's result.
//
// Clocks: where the device times the drawing itself (RasterDevice::device_clock: a GPU with a
// timer), every aliased primitive is drawn by draw_each, and its render_us is the device's time
// around its own draw; host_us is its share of the host's submission and wait. Elsewhere both
// are the host's clock.
//
// Where the lit pixels are found: on the host, over the pixels read back (what `run` does), or,
// with BatchOptions::Scan::kDevice, on the device (platforms/lit_mask.h: a bit per pixel of the
// region's colour comes back instead of the pixels). Same pixels, same proofs either way.
//
// Multisample platforms (PlatformSpec::samples > 0, the antialiasing condition). The primitive is
// drawn white into a multisample window and the expected region is resolved into a single-sample
// one, inside render_us: what antialiasing costs includes the resolve. Resolved colours blend
// with the background, so the colour counter cannot work here: the resolved red value v of a
// pixel gives the number of its samples the primitive covered, k = round(v * samples / 255)
// (llvmpipe, 4 samples: v is one of 0, 64, 128, 191, 255 for k = 0..4; any value more than 1 away
// from 255 k / samples aborts the primitive with the value). Under multisampling the occlusion
// query counts samples, so the proof compares it with the sum of k over the region read.
// Clearing: after the readback the primitive is drawn again in black: the same vertices and state
// but the colour give the same samples (GL invariance; the colour is a vertex attribute), so
// exactly what it lit is cleared, at one more draw outside render_us (a scissored clear cost 2-3x
// more, a whole-window clear of the 4x buffer about 25 ms at 907 x 907). Should a sample stay lit
// anyway, the next primitive's count exposes it (more samples found than passed), and that
// primitive is drawn again on a cleared window, read whole. Multisample primitives are drawn one
// at a time.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "platforms/layer_packing.h"
#include "platforms/lit_mask.h"
#include "platforms/pixel_scan.h"
#include "platforms/platform.h"
#include "platforms/raster_device.h"

namespace ra::platforms {
namespace {

class ReadbackMeasurement : public Platform {
 public:
  ReadbackMeasurement(std::unique_ptr<RasterDevice> device, const rundir::PlatformSpec& spec,
                      ReadbackMethod method, std::vector<uint64_t> wild,
                      const BatchOptions& batching)
      : device_(std::move(device)),
        method_(method),
        wild_pixel_indices_(std::move(wild)),
        name_(spec.name),
        samples_(spec.samples),
        info_(device_->info()) {
    if (samples_ > 0) decode_ = samples_from_resolved(samples_);
    const bool aliased_proof = samples_ == 0 && method_ == ReadbackMethod::kRegionWithProof;
    switch (batching.clock) {
      case BatchOptions::Clock::kAuto:
        device_clock_ = aliased_proof && device_->device_clock();
        break;
      case BatchOptions::Clock::kHost:
        break;
      case BatchOptions::Clock::kDevice:
        if (!info_.timer_query)
          throw std::logic_error("platform " + name_ + " has no timer for the device's clock");
        device_clock_ = aliased_proof;
        break;
    }
    if (batching.scan == BatchOptions::Scan::kDevice) {
      if (!device_->scans())
        throw std::logic_error("platform " + name_ + " cannot find lit pixels on the device");
      device_scan_ = samples_ == 0;
    }
    // As the devices decide their layers (raster_device.h create_gl_device).
    layered_ = aliased_proof && (batching.max_layers > 1 ||
                                 (batching.max_layers == 0 && device_->device_clock()));
  }

  int batch_layers() const override { return layered_ ? device_->layers() : 1; }
  StageTimes stage_times() const override { return stages_; }

  DriverInfo driver_info() const override {
    DriverInfo info = info_;
    info.clock = device_clock_ ? "device" : "host";
    info.layered = layered_;
    return info;
  }

  double measure_timer_over_cpu() override {
    if (!info_.timer_query) return info_.timer_over_cpu;
    device_->bind();
    return info_.timer_over_cpu = device_->timer_over_cpu();
  }

  void set_view(const geometry::View& view) override {
    device_->bind();
    device_->set_view(view);
    clear_all();
  }

  RenderResult render(const geometry::Primitive& prim,
                      const geometry::PixelRegion& expected) override {
    device_->bind();
    if (samples_ > 0) return render_multisample(prim, expected);
    RenderResult out;
    switch (method_) {
      case ReadbackMethod::kDrawOnly:  // the floor: what the renderer itself must spend
        out.render_us = out.host_us = draw_on_device({prim}, {kWhite}, false, nullptr);
        return out;
      case ReadbackMethod::kFullWindow:  // the paper's method: clear, draw, read everything
        clear_all();
        out.render_us = out.host_us = draw_on_device({prim}, {kWhite}, false, nullptr);
        read_colour(window(), kAnyColour, out.lit);
        out.full_scan = true;
        return out;
      case ReadbackMethod::kRegionWithProof:
        break;
    }
    const geometry::Pixel* wild = wild_pixel_for(prim, expected);
    if (device_clock_ && !wild) return render_each({prim}, {expected}, {0}).front();
    reserve_colours(1);
    const uint32_t colour = ++colour_;
    out.render_us = out.host_us = draw_on_device({prim}, {colour}, true, wild);
    const uint64_t fragments = counted_fragments();
    read_colour(expected, colour, out.lit);
    if (uint64_t(out.lit.size()) == fragments) return out;
    out.full_scan = true;
    out.lit.clear();
    read_colour(window(), colour, out.lit);
    if (uint64_t(out.lit.size()) == fragments) return out;
    // Either the colour did not come back exactly, or the driver produced more fragments than
    // pixels: it lit some pixel twice (softpipe does, for some large triangles of the nist2008
    // views: 16,355 fragments for 16,336 pixels in one case). Draw the primitive white on a
    // cleared window and take every non-black pixel of the whole window: complete by
    // construction, whatever the count says.
    redraw_alone(prim, wild, out);
    return out;
  }

  std::vector<RenderResult> render_batch(const std::vector<geometry::Primitive>& prims,
                                         const std::vector<geometry::PixelRegion>& expected,
                                         const std::vector<int>& layers) override {
    device_->bind();
    const bool fits = !prims.empty() && prims.size() <= device_->max_batch() && samples_ == 0;
    if (method_ == ReadbackMethod::kDrawOnly && fits) {  // the batched floor (benchmark only)
      std::vector<RenderResult> out(prims.size());
      const double us =
          draw_on_device(prims, std::vector<uint32_t>(prims.size(), kWhite), false, nullptr);
      for (RenderResult& r : out)
        r.render_us = r.host_us = us / double(prims.size()), r.batch_size = int(prims.size());
      return out;
    }
    if (method_ != ReadbackMethod::kRegionWithProof || !fits)
      return Platform::render_batch(prims, expected);
    for (size_t i = 0; i < prims.size(); ++i)  // the test fault is drawn one primitive at a time
      if (wild_pixel_for(prims[i], expected[i])) return Platform::render_batch(prims, expected);
    const bool one_layer =
        std::all_of(layers.begin(), layers.end(), [](int layer) { return layer == 0; });
    if (!one_layer || device_clock_) {
      if (!layers.empty() && *std::max_element(layers.begin(), layers.end()) >= device_->layers())
        throw std::logic_error("render_batch: a layer beyond the window's " +
                               std::to_string(device_->layers()));
      return render_each(prims, expected,
                         layers.empty() ? std::vector<int>(prims.size(), 0) : layers);
    }
    if (prims.size() < 2) return Platform::render_batch(prims, expected);
    reserve_colours(prims.size());
    std::vector<uint32_t> colours(prims.size());
    for (uint32_t& c : colours) c = ++colour_;
    const double share_us = draw_on_device(prims, colours, true, nullptr) / double(prims.size());
    const uint64_t fragments = counted_fragments();
    std::vector<RenderResult> out(prims.size());
    uint64_t found = 0;
    read_regions(expected, {}, colours);
    for (size_t i = 0; i < prims.size(); ++i) {
      out[i].render_us = out[i].host_us = share_us;
      out[i].batch_size = int(prims.size());
      scan_region(i, colours[i], out[i].lit);
      found += uint64_t(out[i].lit.size());
    }
    if (found == fragments) return out;
    return Platform::render_batch(prims, expected);
  }

 private:
  // Draws each primitive in its own colour into its layer (draw_each: one wait, a count each) and
  // proves each alone; see the top of this file.
  std::vector<RenderResult> render_each(const std::vector<geometry::Primitive>& prims,
                                        const std::vector<geometry::PixelRegion>& expected,
                                        const std::vector<int>& layers) {
    const size_t n = prims.size();
    reserve_colours(n);
    std::vector<uint32_t> colours(n);
    for (uint32_t& c : colours) c = ++colour_;
    const double host_us = draw_each_on_device(prims, colours, layers, device_clock_);
    std::vector<RenderResult> out(n);
    std::vector<uint64_t> fragments(n);
    std::vector<size_t> unproven;
    read_regions(expected, layers, colours);
    for (size_t i = 0; i < n; ++i) {
      out[i].host_us = host_us / double(n);
      out[i].device_clock = device_clock_;
      out[i].render_us = device_clock_ ? device_us_of(i) : out[i].host_us;
      out[i].batch_size = int(n);
      scan_region(i, colours[i], out[i].lit);
      fragments[i] = fragments_of(i);
      if (uint64_t(out[i].lit.size()) != fragments[i]) unproven.push_back(i);
    }
    // Before anything is cleared: each unproven primitive's colour anywhere in its layer.
    std::vector<size_t> redraw;
    for (size_t i : unproven) {
      out[i].full_scan = true;
      out[i].lit.clear();
      read_regions({window()}, {layers[i]}, {colours[i]});
      scan_region(0, colours[i], out[i].lit);
      if (uint64_t(out[i].lit.size()) != fragments[i]) redraw.push_back(i);
    }
    for (size_t i : redraw) {
      out[i].batch_size = 1;
      redraw_alone(prims[i], nullptr, out[i]);
    }
    return out;
  }

  // The last resort for a primitive whose count and pixels disagree (the colour did not come
  // back exactly, or the driver produced more fragments than pixels: softpipe lights some pixels
  // of some large nist2008 triangles twice, 16,355 fragments for 16,336 pixels in one case): the
  // primitive drawn white on a cleared window and every non-black pixel of the whole window taken,
  // complete by construction whatever the count says. Sets out's lit pixels and times.
  void redraw_alone(const geometry::Primitive& prim, const geometry::Pixel* wild,
                    RenderResult& out) {
    clear_all();
    uint64_t again = 0;
    if (device_clock_ && !wild) {
      out.host_us = draw_each_on_device({prim}, {kWhite}, {0}, true);
      out.render_us = device_us_of(0);
      again = fragments_of(0);
    } else {
      out.render_us = out.host_us = draw_on_device({prim}, {kWhite}, true, wild);
      again = counted_fragments();
    }
    out.full_scan = true;
    out.lit.clear();
    read_colour(window(), kAnyColour, out.lit);
    clear_all();
    check_redraw(uint64_t(out.lit.size()), "pixels", again, "fragments", prim.index);
  }

  geometry::PixelRegion window() const {
    return geometry::PixelRegion(geometry::PixelRect{0, 0, device_->width(), device_->height()});
  }

  geometry::PixelRect clamp(geometry::PixelRect r) const {
    r.x0 = std::max(r.x0, 0);
    r.y0 = std::max(r.y0, 0);
    r.x1 = std::min(r.x1, device_->width());
    r.y1 = std::min(r.y1, device_->height());
    return r;
  }

  // The region's rectangles clamped to the window, the empty ones left out.
  std::vector<geometry::PixelRect> clamped(const geometry::PixelRegion& region) const {
    std::vector<geometry::PixelRect> rects;
    for (const geometry::PixelRect& r : region.rects)
      if (!clamp(r).empty()) rects.push_back(clamp(r));
    return rects;
  }

  // Reads every region's rectangles in one readback, region i from layer layers[i] (layer 0 when
  // `layers` is empty); spans_[i] = region i's range in rects_. With the scan on the device,
  // region i is scanned there for colours[i] (one per region; empty: read the pixels).
  void read_regions(const std::vector<geometry::PixelRegion>& regions,
                    const std::vector<int>& layers = {},
                    const std::vector<uint32_t>& colours = {}) {
    rects_.clear();
    spans_.clear();
    rect_layers_.clear();
    rect_colours_.clear();
    for (size_t i = 0; i < regions.size(); ++i) {
      const size_t first = rects_.size();
      for (const geometry::PixelRect& r : clamped(regions[i])) {
        rects_.push_back(r);
        if (!layers.empty()) rect_layers_.push_back(layers[i]);
        if (!colours.empty()) rect_colours_.push_back(colours[i]);
      }
      spans_.emplace_back(first, rects_.size());
    }
    scanned_ = device_scan_ && !colours.empty();
    if (rects_.empty()) return;
    const auto t0 = std::chrono::steady_clock::now();
    if (scanned_) device_->scan(rects_, rect_layers_, rect_colours_);
    else device_->read(rects_, rect_layers_);
    stages_.transfer_us += micros_since(t0);
  }

  // Appends the pixels of region i (read by read_regions) in `colour` (kAnyColour: any that is not
  // black) to `lit`. The runs of several rectangles side by side (a line's strip: rows interleave)
  // are put in (y, x) order before they join `lit`.
  void scan_region(size_t i, uint32_t colour, geometry::PixelSet& lit) {
    const auto t0 = std::chrono::steady_clock::now();
    scan_region_untimed(i, colour, lit);
    stages_.host_scan_us += micros_since(t0);
  }
  void scan_region_untimed(size_t i, uint32_t colour, geometry::PixelSet& lit) {
    const auto [first, last] = spans_[i];
    const bool any = colour == kAnyColour, top_down = device_->rows_top_down();
    auto scan = [&](size_t k, geometry::PixelSet& into) {
      const geometry::PixelRect& r = rects_[k];
      if (!scanned_)
        return scan_rect(device_->pixels(k), size_t(r.x1 - r.x0), top_down, r, any, colour, into);
      if (rect_colours_[k] != colour)
        throw std::logic_error("scan_region: scanned on the device for another colour");
      append_mask_runs(device_->mask(k), uint32_t(r.x1 - r.x0 + 31) / 32, top_down, r, into);
    };
    if (last - first == 1) return scan(first, lit);
    runs_.clear();
    geometry::PixelSet part;
    for (size_t k = first; k < last; ++k) {
      part.clear();
      scan(k, part);
      runs_.insert(runs_.end(), part.runs().begin(), part.runs().end());
    }
    append_in_order(runs_, lit);
  }

  void read_colour(const geometry::PixelRegion& region, uint32_t colour, geometry::PixelSet& lit) {
    read_regions({region}, {}, {colour});
    scan_region(0, colour, lit);
  }

  // --- multisample platforms -------------------------------------------------------------------

  RenderResult render_multisample(const geometry::Primitive& prim,
                                  const geometry::PixelRegion& expected) {
    RenderResult out;
    out.samples = samples_;
    const geometry::PixelRegion whole = window();
    switch (method_) {
      case ReadbackMethod::kDrawOnly:  // the floor: drawing alone, no resolve
        out.render_us = out.host_us = draw_on_device({prim}, {kWhite}, false, nullptr);
        draw_on_device({prim}, {0}, false, nullptr);
        return out;
      case ReadbackMethod::kFullWindow:
        clear_all();
        out.render_us = out.host_us = draw_resolved(prim, nullptr, whole, false);
        read_coverage(whole, out);
        out.full_scan = true;
        clear_all();
        return out;
      case ReadbackMethod::kRegionWithProof:
        break;
    }
    const geometry::Pixel* wild = wild_pixel_for(prim, expected);
    out.render_us = out.host_us = draw_resolved(prim, wild, expected, true);
    uint64_t passed = counted_fragments();
    if (read_coverage(expected, out) == passed) {
      draw_on_device({prim}, {0}, false, wild);  // black: exactly its samples go back to black
      return out;
    }
    out.full_scan = true;
    device_->resolve(clamped(whole));
    uint64_t found = read_coverage(whole, out);
    clear_all();
    if (found == passed) return out;
    // More samples found than passed: some stayed lit from an earlier primitive; fewer: the driver
    // covered some sample twice. Draw again on the cleared window and read it whole.
    out.render_us = out.host_us = draw_resolved(prim, wild, whole, true);
    passed = counted_fragments();
    found = read_coverage(whole, out);
    clear_all();
    check_redraw(found, "samples", passed, "samples passed", prim.index);
    return out;
  }

  // Draws the primitive white and resolves `region` in the same timed submission.
  double draw_resolved(const geometry::Primitive& prim, const geometry::Pixel* wild,
                       const geometry::PixelRegion& region, bool counted) {
    const std::vector<geometry::PixelRect> rects = clamped(region);
    return draw_on_device({prim}, {kWhite}, counted, wild, &rects);
  }

  // Reads the region's resolved pixels and replaces out.lit / out.samples_lit with those that
  // have any coverage, in (y, x) order; returns the sum of their samples lit.
  uint64_t read_coverage(const geometry::PixelRegion& region, RenderResult& out) {
    read_regions({region});
    covered_.clear();
    const bool top_down = device_->rows_top_down();
    for (size_t k = spans_[0].first; k < spans_[0].second; ++k) {
      const geometry::PixelRect& r = rects_[k];
      const int w = r.x1 - r.x0, h = r.y1 - r.y0;
      for (int y = 0; y < h; ++y) {
        const uint32_t* row = device_->pixels(k) + size_t(top_down ? h - 1 - y : y) * w;
        for (int x = 0; x < w; ++x) {
          const uint8_t v = uint8_t(row[x]);  // red: the low byte of a little-endian RGBA8 pixel
          if (v == 0) continue;
          const uint8_t k_lit = decode_[v];
          if (k_lit == 255)
            throw std::runtime_error("platform " + name_ + ": resolved value " +
                                     std::to_string(v) + " at pixel (" + std::to_string(r.x0 + x) +
                                     ", " + std::to_string(r.y0 + y) + ") is no multiple of 255/" +
                                     std::to_string(samples_));
          covered_.push_back({r.y0 + y, r.x0 + x, k_lit});
        }
      }
    }
    if (spans_[0].second - spans_[0].first > 1)  // a line's strip: put in (y, x) order
      std::sort(covered_.begin(), covered_.end(), [](const Covered& a, const Covered& b) {
        return a.y != b.y ? a.y < b.y : a.x < b.x;
      });
    out.lit.clear();
    out.samples_lit.clear();
    out.samples_lit.reserve(covered_.size());
    uint64_t sum = 0;
    for (const Covered& c : covered_) {
      out.lit.append_run(c.y, c.x, c.x + 1);
      out.samples_lit.push_back(c.k);
      sum += c.k;
    }
    return sum;
  }

  // --- upkeep ----------------------------------------------------------------------------------

  // The device's draws, their host time added to stages_.
  double draw_on_device(const std::vector<geometry::Primitive>& prims,
                        const std::vector<uint32_t>& colours, bool counted,
                        const geometry::Pixel* wild,
                        const std::vector<geometry::PixelRect>* resolve = nullptr) {
    const double us = device_->draw(prims, colours, counted, wild, resolve);
    stages_.draw_us += us;
    return us;
  }
  double draw_each_on_device(const std::vector<geometry::Primitive>& prims,
                             const std::vector<uint32_t>& colours, const std::vector<int>& layers,
                             bool timed) {
    const double us = device_->draw_each(prims, colours, layers, timed);
    stages_.draw_us += us;
    return us;
  }

  // The device's time of primitive i of the last timed draw_each, added to stages_.
  double device_us_of(size_t i) {
    const auto t0 = std::chrono::steady_clock::now();
    const double us = device_->device_us_of(i);
    stages_.results_us += micros_since(t0);
    if (std::isfinite(us)) stages_.device_us += us;
    return us;
  }
  // The occlusion counts, the time of fetching them added to stages_.
  uint64_t counted_fragments() {
    const auto t0 = std::chrono::steady_clock::now();
    const uint64_t n = device_->counted_fragments();
    stages_.results_us += micros_since(t0);
    return n;
  }
  uint64_t fragments_of(size_t i) {
    const auto t0 = std::chrono::steady_clock::now();
    const uint64_t n = device_->fragments_of(i);
    stages_.results_us += micros_since(t0);
    return n;
  }

  static double micros_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  }

  // The last word on a primitive redrawn on a cleared window and read whole: more lit than the
  // driver counted cannot be (the primitive fails); fewer means the driver lit some pixel or
  // sample twice, which is said and kept.
  static void check_redraw(uint64_t found, const char* found_unit, uint64_t counted,
                           const char* counted_unit, uint64_t primitive) {
    if (found > counted)
      throw std::runtime_error("the driver lit " + std::to_string(found) + " " + found_unit +
                               " with " + std::to_string(counted) + " " + counted_unit +
                               " for primitive " + std::to_string(primitive));
    if (found < counted)
      std::fprintf(stderr, "primitive %llu: %llu %s for %llu %s (lit twice)\n",
                   static_cast<unsigned long long>(primitive),
                   static_cast<unsigned long long>(counted), counted_unit,
                   static_cast<unsigned long long>(found), found_unit);
  }

  // Makes room for n more colours before the 24-bit counter reaches kWhite (the redraw's colour):
  // after 16.7 million primitives in one view.
  void reserve_colours(size_t n) {
    if (colour_ + n > kWhite - 1) clear_all();
  }

  // Clears the whole window (a fast path in Mesa, unlike a scissored clear) and restarts colours.
  void clear_all() {
    const auto t0 = std::chrono::steady_clock::now();
    device_->clear();
    stages_.clear_us += micros_since(t0);
    colour_ = 0;
  }

  // Test-only fault: where the extra pixel goes (the quadrant opposite the expected region), or
  // nullptr when this primitive has none.
  const geometry::Pixel* wild_pixel_for(const geometry::Primitive& prim,
                                        const geometry::PixelRegion& region) {
    if (std::find(wild_pixel_indices_.begin(), wild_pixel_indices_.end(), prim.index) ==
        wild_pixel_indices_.end())
      return nullptr;
    wild_ = opposite_quadrant_pixel(region, device_->width(), device_->height());
    return &wild_;
  }

  std::unique_ptr<RasterDevice> device_;
  ReadbackMethod method_;
  std::vector<uint64_t> wild_pixel_indices_;
  std::string name_;  // the platform's name, for messages
  int samples_ = 0;   // PlatformSpec::samples; 0 = aliased
  DriverInfo info_;
  uint32_t colour_ = 0;  // of the last primitive drawn; 0 (black) = none since the last clear
  std::array<uint8_t, 256> decode_{};  // resolved red value -> samples lit (255: invalid)
  std::vector<geometry::PixelRect> rects_;             // of the last read_regions
  std::vector<std::pair<size_t, size_t>> spans_;       // region i -> [first, last) of rects_
  std::vector<int> rect_layers_;                       // the layer of each of rects_ (or empty)
  std::vector<uint32_t> rect_colours_;  // the colour each of rects_ was scanned for on the device
  bool scanned_ = false;      // the last read_regions scanned on the device: masks, not pixels
  bool device_scan_ = false;  // BatchOptions::Scan::kDevice (aliased windows)
  StageTimes stages_;         // where the time went (stage_times)
  bool layered_ = false;       // batches may use the device's layers (aliased, region with proof)
  bool device_clock_ = false;  // render_us from the device's timestamps (see the top)
  std::vector<geometry::PixelRun> runs_;
  struct Covered {
    int32_t y, x;
    uint8_t k;
  };
  std::vector<Covered> covered_;
  geometry::Pixel wild_;
};

}  // namespace

std::unique_ptr<Platform> create_gl_platform(const rundir::PlatformSpec& spec, ReadbackMethod method,
                                             std::vector<uint64_t> wild_pixel_indices,
                                             const BatchOptions& batching) {
  return std::make_unique<ReadbackMeasurement>(create_gl_device(spec, batching.max_layers), spec,
                                               method, std::move(wild_pixel_indices), batching);
}

std::unique_ptr<Platform> create_vulkan_platform(const rundir::PlatformSpec& spec, ReadbackMethod method,
                                                 std::vector<uint64_t> wild_pixel_indices,
                                                 const BatchOptions& batching) {
  return std::make_unique<ReadbackMeasurement>(create_vulkan_device(spec, batching.max_layers),
                                               spec, method, std::move(wild_pixel_indices),
                                               batching);
}

}  // namespace ra::platforms
