// A GL driver as a platform: the measurement of every GL back end (OSMesa, Mesa's surfaceless EGL,
// an EGL device), one code path. The context comes from platforms/gl_context.h; every GL call goes
// through its function table.
//
// Drawing goes to a framebuffer object of the view's size, never to a window-system buffer (EGL
// has none here; OSMesa's: glFinish on it copies the whole window into the caller's memory, about
// 150 us at 907x907, 30x the cost of drawing one primitive); with an FBO only the pixels read back
// are copied, by glReadPixels.
//
// Completeness of the readback: only the expected region is scanned, and an occlusion query
// (GL_SAMPLES_PASSED) counts the fragments the primitive produced. Without multisampling and with
// no depth or stencil test, every fragment of one point, line or polygon lights a distinct pixel, so
// when the count equals the number of lit pixels found in the region nothing was lit elsewhere;
// when it differs, the whole window is scanned (RenderResult::full_scan).
//
// No clear between primitives: each primitive is drawn in its own colour (a 24-bit counter) and its
// pixels are those holding exactly that colour. Coverage does not depend on the colour (it is a
// vertex attribute, not a rasterization parameter), and a scissored clear is a quad draw in Mesa:
// it cost 1.7x (llvmpipe) to 1.8x (softpipe) the drawing of a large 907x907 triangle. Should a
// driver not return the colour exactly, or leave pixels of another colour, the full scan still
// disagrees with the count and the primitive is drawn again the old way: whole window cleared,
// white, every non-black pixel taken (the end of render()).
//
// Multisample platforms (PlatformSpec::samples > 0, the antialiasing condition). The primitive is
// drawn into a multisample FBO (GL_RGBA8, `samples` samples per pixel, GL_MULTISAMPLE enabled) and
// the expected region is resolved (glBlitFramebuffer) into a single-sample FBO that glReadPixels
// reads. Resolved colours blend with the background, so the colour counter cannot work here: every
// primitive is drawn white on black and the resolved red value v of a pixel gives the number of its
// samples the primitive covered, k = round(v * samples / 255) (llvmpipe, 4 samples: v is one of
// 0, 64, 128, 191, 255 for k = 0..4, i.e. 255 k / 4 rounded to nearest; any value more than 1 away
// from 255 k / samples aborts the primitive with the value). Sample positions (llvmpipe 4x, from
// glGetMultisamplefv): (0.375, 0.125), (0.875, 0.375), (0.125, 0.625), (0.625, 0.875).
// render_us = draw + resolve of the expected region + glFinish: what antialiasing costs includes
// the resolve.
// Completeness: under multisampling GL_SAMPLES_PASSED counts samples, not fragments, so the proof
// compares it with the sum of k over the region read (each covered sample of one point, line or
// triangle is covered once); when they differ the whole window is resolved and read.
// Clearing: after the readback the primitive is drawn again in the clear colour (black, alpha 0):
// the same vertices and state but the colour give the same samples (GL invariance; the colour is
// a vertex attribute), so exactly what it lit is cleared. This costs one more draw, outside
// render_us; a scissored clear (a quad draw in Mesa) cost 2-3x more, and a whole-window clear of
// the 4x buffer about 25 ms at 907 x 907. After a whole-window scan the whole window is cleared.
// Should a sample stay lit anyway, the next primitive's count exposes it (more samples found than
// passed), and that primitive is drawn again on a cleared window, read whole. The colour-counter
// batching is not used (render_batch draws one primitive at a time).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <vector>

#include "platforms/gl_context.h"
#include "platforms/pixel_scan.h"
#include "platforms/platform.h"

namespace ra::platforms {
namespace {

constexpr uint32_t kRgb = kRgbMask;  // RGB bytes of a little-endian RGBA8 pixel
constexpr uint32_t kAnyColour = 0xffffffffu;
constexpr uint32_t kLastColour = 0x00ffffffu;

class GlPlatform : public Platform {
 public:
  GlPlatform(const PlatformSpec& spec, ReadbackMethod method, std::vector<uint64_t> wild)
      : method_(method), wild_pixel_indices_(std::move(wild)), name_(spec.name),
        samples_(spec.samples) {
    context_ = create_gl_context(spec);  // sets Mesa's environment and checks the driver
    info_.backend = context_->backend();
    gl().GenFramebuffers(1, &framebuffer_);
    gl().BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    gl().GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size_);
    gl().GenQueries(1, &query_);
    if (samples_ > 0) init_multisample();

    const char* ext = reinterpret_cast<const char*>(gl().GetString(GL_EXTENSIONS));
    info_.renderer = reinterpret_cast<const char*>(gl().GetString(GL_RENDERER));
    info_.version = reinterpret_cast<const char*>(gl().GetString(GL_VERSION));
    info_.vendor = reinterpret_cast<const char*>(gl().GetString(GL_VENDOR));
    GLint bits = 0;
    gl().GetIntegerv(GL_SUBPIXEL_BITS, &bits);
    info_.subpixel_bits = bits;
    info_.timer_query = ext && std::strstr(ext, "GL_ARB_timer_query");
    GLint max_samples = 0;
    gl().GetIntegerv(GL_MAX_SAMPLES, &max_samples);
    info_.max_samples = max_samples;

    // The paper's conditions: white on black, size/width 1, no antialiasing, both faces filled.
    for (GLenum cap : {GL_DEPTH_TEST, GL_LIGHTING, GL_DITHER, GL_POINT_SMOOTH, GL_LINE_SMOOTH,
                       GL_POLYGON_SMOOTH, GL_MULTISAMPLE, GL_CULL_FACE, GL_BLEND, GL_SCISSOR_TEST})
      gl().Disable(cap);
    gl().PointSize(1);
    gl().LineWidth(1);
    gl().PolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    gl().ClearColor(0, 0, 0, 0);
    gl().Color4f(1, 1, 1, 1);
    gl().PixelStorei(GL_PACK_ALIGNMENT, 4);
    if (samples_ > 0) gl().Enable(GL_MULTISAMPLE);  // the antialiasing condition
  }

  DriverInfo driver_info() const override { return info_; }

  double measure_timer_over_cpu() override {
    if (!info_.timer_query) return info_.timer_over_cpu;
    make_current();
    return info_.timer_over_cpu = timer_over_cpu();
  }

  void set_view(const geometry::View& view) override {
    make_current();
    if (view.width != width_ || view.height != height_) resize(view.width, view.height);
    gl().Viewport(0, 0, width_, height_);
    if (!warmed_up_) warm_up();
    gl().MatrixMode(GL_PROJECTION);
    gl().LoadMatrixd(view.projection.m.data());
    gl().MatrixMode(GL_MODELVIEW);
    gl().LoadMatrixd(view.view_matrix.m.data());
    clear_all();
  }

  RenderResult render(const geometry::Primitive& prim,
                      const geometry::PixelRegion& expected) override {
    make_current();
    if (samples_ > 0) return render_multisample(prim, expected);
    RenderResult out;
    switch (method_) {
      case ReadbackMethod::kDrawOnly:  // the floor: what the renderer itself must spend
        out.render_us = draw_and_finish(prim);
        return out;
      case ReadbackMethod::kFullWindow:  // the paper's method: clear, draw, read everything
        gl().Clear(GL_COLOR_BUFFER_BIT);
        gl().Finish();  // keep the clear out of render_us
        out.render_us = draw_and_finish(prim);
        read_and_scan({0, 0, width_, height_}, kAnyColour, out.lit);
        out.full_scan = true;
        return out;
      case ReadbackMethod::kRegionWithProof:
        break;
    }
    reserve_colours(1);
    use_colour(++colour_);
    const geometry::Pixel* wild = wild_pixel_for(prim, expected);
    gl().BeginQuery(GL_SAMPLES_PASSED, query_);
    out.render_us = draw_and_finish(prim, true, wild);
    GLuint samples = 0;
    gl().GetQueryObjectuiv(query_, GL_QUERY_RESULT, &samples);

    read_and_scan(expected, colour_, out.lit);
    if (out.lit.size() == samples) return out;
    out.full_scan = true;
    out.lit.clear();
    read_and_scan({0, 0, width_, height_}, colour_, out.lit);
    if (out.lit.size() == samples) return out;
    // Either the colour did not come back exactly, or the driver produced more fragments than
    // pixels: it lit some pixel twice (softpipe does, for some large triangles of the nist2008
    // views: 16,355 fragments for 16,336 pixels in one case). Draw
    // the primitive white on a cleared window and take every non-black pixel of the whole window:
    // complete by construction, whatever the count says.
    clear_all();
    gl().Color4ub(255, 255, 255, 255);
    gl().BeginQuery(GL_SAMPLES_PASSED, query_);
    out.render_us = draw_and_finish(prim, true, wild);
    gl().GetQueryObjectuiv(query_, GL_QUERY_RESULT, &samples);
    out.lit.clear();
    read_and_scan({0, 0, width_, height_}, kAnyColour, out.lit);
    clear_all();
    if (out.lit.size() > samples)  // more lit pixels than fragments on a cleared window
      throw std::runtime_error("the driver lit " + std::to_string(out.lit.size()) +
                               " pixels with " + std::to_string(samples) +
                               " fragments for primitive " + std::to_string(prim.index));
    if (out.lit.size() < samples)
      std::fprintf(stderr, "primitive %llu: %u fragments for %lld pixels (pixels lit twice)\n",
                   static_cast<unsigned long long>(prim.index), samples,
                   static_cast<long long>(out.lit.size()));
    return out;
  }

  // A batch: each primitive in its own colour, one occlusion query and one glFinish around them
  // all (a glFinish per primitive cost more than the small primitive's drawing: llvmpipe walks all
  // its tiles at every flush). The sum over the batch of the pixels found in each primitive's
  // region with its colour equals the fragment count only when every fragment was found where it
  // belongs and none was overwritten by another (each found pixel is a distinct fragment); any
  // other outcome redraws the batch one primitive at a time, each with its own proof and time.
  std::vector<RenderResult> render_batch(
      const std::vector<geometry::Primitive>& prims,
      const std::vector<geometry::PixelRegion>& expected) override {
    make_current();
    if (method_ == ReadbackMethod::kDrawOnly) return draw_batch_only(prims);
    if (method_ != ReadbackMethod::kRegionWithProof || prims.size() < 2 || samples_ > 0)
      return Platform::render_batch(prims, expected);
    reserve_colours(prims.size());
    const uint32_t first = colour_ + 1;
    std::vector<RenderResult> out(prims.size());
    const auto t0 = std::chrono::steady_clock::now();
    gl().BeginQuery(GL_SAMPLES_PASSED, query_);
    for (size_t i = 0; i < prims.size(); ++i) {
      use_colour(++colour_);
      draw(prims[i], wild_pixel_for(prims[i], expected[i]));
    }
    gl().EndQuery(GL_SAMPLES_PASSED);
    gl().Finish();
    const double share_us =
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() /
        double(prims.size());
    GLuint samples = 0;
    gl().GetQueryObjectuiv(query_, GL_QUERY_RESULT, &samples);
    int64_t found = 0;
    for (size_t i = 0; i < prims.size(); ++i) {
      out[i].render_us = share_us;
      out[i].batch_size = int(prims.size());
      read_and_scan(expected[i], first + uint32_t(i), out[i].lit);
      found += out[i].lit.size();
    }
    if (found == int64_t(samples)) return out;
    return Platform::render_batch(prims, expected);
  }

 private:
  const GlApi& gl() const { return context_->gl(); }

  // Several platforms in one process (tests: an aliased and a multisample one side by side) each
  // have their own context; GL calls go to the current one.
  void make_current() {
    context_->make_current();
  }

  // The multisample FBO's entry points and its resolve target; fails, naming the platform, when the
  // driver cannot give `samples_` samples per pixel.
  void init_multisample() {
    GLint max_samples = 0;
    gl().GetIntegerv(GL_MAX_SAMPLES, &max_samples);
    if (max_samples < samples_)
      throw std::runtime_error("platform " + name_ + " needs " + std::to_string(samples_) +
                               " samples per pixel, but this driver (" +
                               reinterpret_cast<const char*>(gl().GetString(GL_RENDERER)) +
                               ") has GL_MAX_SAMPLES " + std::to_string(max_samples));
    gl().GenFramebuffers(1, &resolve_framebuffer_);
    // k samples lit <-> resolved value 255 k / samples rounded either way; anything else is 255.
    decode_ = samples_from_resolved(samples_);
  }

  // Multisample rendering (the antialiasing condition; see the top of this file).
  RenderResult render_multisample(const geometry::Primitive& prim,
                                  const geometry::PixelRegion& expected) {
    RenderResult out;
    out.samples = samples_;
    const geometry::PixelRegion window = geometry::PixelRect{0, 0, width_, height_};
    gl().Color4ub(255, 255, 255, 255);
    switch (method_) {
      case ReadbackMethod::kDrawOnly:  // the floor: drawing alone, no resolve
        out.render_us = draw_and_finish(prim);
        erase(prim, nullptr);
        return out;
      case ReadbackMethod::kFullWindow:
        clear_all();
        out.render_us = draw_resolve_finish(prim, nullptr, window);
        read_coverage(window, out);
        out.full_scan = true;
        clear_all();
        return out;
      case ReadbackMethod::kRegionWithProof:
        break;
    }
    const geometry::Pixel* wild = wild_pixel_for(prim, expected);
    gl().BeginQuery(GL_SAMPLES_PASSED, query_);
    out.render_us = draw_resolve_finish(prim, wild, expected, true);
    GLuint passed = 0;
    gl().GetQueryObjectuiv(query_, GL_QUERY_RESULT, &passed);
    int64_t found = read_coverage(expected, out);
    if (found == int64_t(passed)) {
      erase(prim, wild);
      return out;
    }
    out.full_scan = true;
    resolve(window);
    found = read_coverage(window, out);
    clear_all();
    if (found == int64_t(passed)) return out;
    // More samples found than passed: some stayed lit from an earlier primitive; fewer: the driver
    // covered some sample twice. Draw again on the cleared window and read it whole.
    gl().BeginQuery(GL_SAMPLES_PASSED, query_);
    out.render_us = draw_resolve_finish(prim, wild, expected, true);
    gl().GetQueryObjectuiv(query_, GL_QUERY_RESULT, &passed);
    resolve(window);
    found = read_coverage(window, out);
    clear_all();
    if (found > int64_t(passed))
      throw std::runtime_error("the driver lit " + std::to_string(found) + " samples with " +
                               std::to_string(passed) + " samples passed for primitive " +
                               std::to_string(prim.index));
    if (found < int64_t(passed))
      std::fprintf(stderr, "primitive %llu: %u samples passed for %lld samples lit (lit twice)\n",
                   static_cast<unsigned long long>(prim.index), passed,
                   static_cast<long long>(found));
    return out;
  }

  // Draws, resolves `region` into the single-sample FBO and waits; returns the CPU time, us.
  double draw_resolve_finish(const geometry::Primitive& prim, const geometry::Pixel* wild,
                             const geometry::PixelRegion& region, bool end_query = false) {
    const auto t0 = std::chrono::steady_clock::now();
    draw(prim, wild);
    if (end_query) gl().EndQuery(GL_SAMPLES_PASSED);
    resolve(region);
    gl().Finish();
    return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  }

  // Resolves the region's rectangles from the multisample FBO into the resolve FBO (same place).
  void resolve(const geometry::PixelRegion& region) {
    gl().BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
    gl().BindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_framebuffer_);
    for (const geometry::PixelRect& r : region.rects) {
      const geometry::PixelRect c = clamp(r);
      if (!c.empty())
        gl().BlitFramebuffer(c.x0, c.y0, c.x1, c.y1, c.x0, c.y0, c.x1, c.y1, GL_COLOR_BUFFER_BIT,
                          GL_NEAREST);
    }
    // Steady state: draw (and clear) into the multisample FBO, read from the resolved one.
    gl().BindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer_);
    gl().BindFramebuffer(GL_READ_FRAMEBUFFER, resolve_framebuffer_);
  }

  // Draws the primitive again in the clear colour: exactly its samples go back to black.
  void erase(const geometry::Primitive& prim, const geometry::Pixel* wild) {
    gl().Color4ub(0, 0, 0, 0);
    draw(prim, wild);
    gl().Finish();
    gl().Color4ub(255, 255, 255, 255);
  }

  // Reads the region's resolved pixels and replaces out.lit / out.samples_lit with those that
  // have any coverage; returns the sum of their samples lit.
  int64_t read_coverage(const geometry::PixelRegion& region, RenderResult& out) {
    covered_.clear();
    size_t rects = 0;
    for (const geometry::PixelRect& r0 : region.rects) {
      const geometry::PixelRect r = clamp(r0);
      if (r.empty()) continue;
      ++rects;
      const int w = r.x1 - r.x0, h = r.y1 - r.y0;
      readback_.resize(size_t(w) * h);
      gl().ReadPixels(r.x0, r.y0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, readback_.data());
      for (int y = 0; y < h; ++y) {
        const uint32_t* row = readback_.data() + size_t(y) * w;
        for (int x = 0; x < w; ++x) {
          const uint8_t v = uint8_t(row[x]);  // red: the low byte of a little-endian RGBA8 pixel
          if (v == 0) continue;
          const uint8_t k = decode_[v];
          if (k == 255)
            throw std::runtime_error("platform " + name_ + ": resolved value " +
                                     std::to_string(v) + " at pixel (" + std::to_string(r.x0 + x) +
                                     ", " + std::to_string(r.y0 + y) + ") is no multiple of 255/" +
                                     std::to_string(samples_));
          covered_.push_back({r.y0 + y, r.x0 + x, k});
        }
      }
    }
    if (rects > 1)  // a line's strip: rectangles side by side, put in (y, x) order
      std::sort(covered_.begin(), covered_.end(), [](const Covered& a, const Covered& b) {
        return a.y != b.y ? a.y < b.y : a.x < b.x;
      });
    out.lit.clear();
    out.samples_lit.clear();
    out.samples_lit.reserve(covered_.size());
    int64_t sum = 0;
    for (const Covered& c : covered_) {
      out.lit.append_run(c.y, c.x, c.x + 1);
      out.samples_lit.push_back(c.k);
      sum += c.k;
    }
    return sum;
  }

  // Draws the primitive and waits for it; returns the CPU time in microseconds. With
  // `end_query`, the running occlusion query is ended right after the draw.
  double draw_and_finish(const geometry::Primitive& prim, bool end_query = false,
                         const geometry::Pixel* wild = nullptr) {
    const auto t0 = std::chrono::steady_clock::now();
    draw(prim, wild);
    if (end_query) gl().EndQuery(GL_SAMPLES_PASSED);
    gl().Finish();
    return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  }

  void draw(const geometry::Primitive& prim, const geometry::Pixel* wild) {
    static const GLenum modes[] = {GL_POINTS, GL_LINES, GL_TRIANGLES};
    gl().Begin(modes[int(prim.kind)]);
    for (int i = 0; i < geometry::vertex_count(prim.kind); ++i)
      gl().Vertex3d(prim.v[i].x, prim.v[i].y, prim.v[i].z);
    gl().End();
    if (wild) draw_wild_pixel(*wild);
  }

  // The batched floor (benchmark only): the batch drawn under one glFinish, nothing read back.
  std::vector<RenderResult> draw_batch_only(const std::vector<geometry::Primitive>& prims) {
    std::vector<RenderResult> out(prims.size());
    const auto t0 = std::chrono::steady_clock::now();
    for (const geometry::Primitive& prim : prims) draw(prim, nullptr);
    gl().Finish();
    const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    for (RenderResult& r : out) r.render_us = us / double(prims.size()), r.batch_size = int(prims.size());
    return out;
  }

  // Test-only fault: where the extra pixel goes (the quadrant opposite the expected region), or
  // nullptr when this primitive has none.
  const geometry::Pixel* wild_pixel_for(const geometry::Primitive& prim,
                                        const geometry::PixelRegion& region) {
    if (std::find(wild_pixel_indices_.begin(), wild_pixel_indices_.end(), prim.index) ==
        wild_pixel_indices_.end())
      return nullptr;
    wild_ = opposite_quadrant_pixel(region, width_, height_);
    return &wild_;
  }

  // Lights pixel p through GL (so only the readback can find it): a point at its centre in NDC.
  void draw_wild_pixel(geometry::Pixel p) {
    gl().MatrixMode(GL_PROJECTION);
    gl().PushMatrix();
    gl().LoadIdentity();
    gl().MatrixMode(GL_MODELVIEW);
    gl().PushMatrix();
    gl().LoadIdentity();
    gl().Begin(GL_POINTS);
    gl().Vertex2d(2.0 * (p.x + 0.5) / width_ - 1.0, 2.0 * (p.y + 0.5) / height_ - 1.0);
    gl().End();
    gl().PopMatrix();
    gl().MatrixMode(GL_PROJECTION);
    gl().PopMatrix();
    gl().MatrixMode(GL_MODELVIEW);
  }

  // GL_TIME_ELAPSED against the CPU clock over the same draws: 8 rounds of 16 window-filling
  // quads at 256 x 256, each round between two glFinish; the median of the rounds' ratios. Near 1
  // where the timer measures what the CPU waits for (llvmpipe times its own rasterization on the
  // CPU); a GPU that runs while the CPU submits shows less. Leaves the window at 256 x 256 and the
  // matrices at identity: set_view() sets all of it again.
  double timer_over_cpu() {
    resize(256, 256);
    gl().Viewport(0, 0, 256, 256);
    gl().MatrixMode(GL_PROJECTION);
    gl().LoadIdentity();
    gl().MatrixMode(GL_MODELVIEW);
    gl().LoadIdentity();
    GLuint query = 0;
    gl().GenQueries(1, &query);
    std::vector<double> ratios;
    for (int round = 0; round < 8; ++round) {
      gl().Finish();
      const auto t0 = std::chrono::steady_clock::now();
      gl().BeginQuery(GL_TIME_ELAPSED, query);
      for (int i = 0; i < 16; ++i) {
        gl().Begin(GL_TRIANGLES);
        for (const double* v : {kQuad[0], kQuad[1], kQuad[2], kQuad[0], kQuad[2], kQuad[3]})
          gl().Vertex2d(v[0], v[1]);
        gl().End();
      }
      gl().EndQuery(GL_TIME_ELAPSED);
      gl().Finish();
      const double cpu_ns =
          std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
      GLuint64 gl_ns = 0;
      gl().GetQueryObjectui64v(query, GL_QUERY_RESULT, &gl_ns);
      if (cpu_ns > 0) ratios.push_back(double(gl_ns) / cpu_ns);
    }
    clear_all();
    if (ratios.empty()) return std::numeric_limits<double>::quiet_NaN();
    std::sort(ratios.begin(), ratios.end());
    return 0.5 * (ratios[(ratios.size() - 1) / 2] + ratios[ratios.size() / 2]);
  }
  static constexpr double kQuad[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};  // NDC corners

  // One small point, line and triangle drawn untimed before the first primitive: the driver
  // compiles its shaders for this state at the first draw (about 7 ms on llvmpipe), which would
  // otherwise land in the first primitive's render_us. Cleared by set_view().
  void warm_up() {
    gl().MatrixMode(GL_PROJECTION);
    gl().LoadIdentity();
    gl().MatrixMode(GL_MODELVIEW);
    gl().LoadIdentity();
    gl().Color4f(1, 1, 1, 1);
    gl().Begin(GL_POINTS);
    gl().Vertex2d(0, 0);
    gl().End();
    gl().Begin(GL_LINES);
    gl().Vertex2d(-0.01, 0);
    gl().Vertex2d(0.01, 0.005);
    gl().End();
    gl().Begin(GL_TRIANGLES);
    gl().Vertex2d(-0.01, -0.01);
    gl().Vertex2d(0.01, -0.01);
    gl().Vertex2d(0, 0.01);
    gl().End();
    gl().Finish();
    warmed_up_ = true;
  }

  void resize(int w, int h) {
    if (w > max_size_ || h > max_size_)
      throw std::runtime_error("window " + std::to_string(w) + "x" + std::to_string(h) +
                               " exceeds this driver's GL_MAX_RENDERBUFFER_SIZE " +
                               std::to_string(max_size_));
    if (samples_ > 0) return resize_multisample(w, h);
    if (renderbuffer_) gl().DeleteRenderbuffers(1, &renderbuffer_);
    gl().GenRenderbuffers(1, &renderbuffer_);
    gl().BindRenderbuffer(GL_RENDERBUFFER, renderbuffer_);
    gl().RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    gl().FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, renderbuffer_);
    if (gl().CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("incomplete framebuffer for a " + std::to_string(w) + "x" +
                               std::to_string(h) + " window");
    width_ = w;
    height_ = h;
  }

  // The multisample FBO (drawn into) and the single-sample resolve FBO (read back), both w x h.
  void resize_multisample(int w, int h) {
    const std::string size = std::to_string(w) + "x" + std::to_string(h);
    if (renderbuffer_) gl().DeleteRenderbuffers(1, &renderbuffer_);
    if (resolve_renderbuffer_) gl().DeleteRenderbuffers(1, &resolve_renderbuffer_);
    gl().GenRenderbuffers(1, &renderbuffer_);
    gl().BindRenderbuffer(GL_RENDERBUFFER, renderbuffer_);
    gl().RenderbufferStorageMultisample(GL_RENDERBUFFER, samples_, GL_RGBA8, w, h);
    GLint got = 0;  // GL may give more samples than asked for: coverage would then be k / got
    gl().GetRenderbufferParameteriv(GL_RENDERBUFFER, GL_RENDERBUFFER_SAMPLES, &got);
    if (got != samples_)
      throw std::runtime_error("platform " + name_ + ": asked for " + std::to_string(samples_) +
                               " samples per pixel, the driver gave " + std::to_string(got));
    gl().BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    gl().FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, renderbuffer_);
    if (gl().CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("incomplete multisample framebuffer for a " + size + " window");
    gl().GenRenderbuffers(1, &resolve_renderbuffer_);
    gl().BindRenderbuffer(GL_RENDERBUFFER, resolve_renderbuffer_);
    gl().RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    gl().BindFramebuffer(GL_FRAMEBUFFER, resolve_framebuffer_);
    gl().FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                              resolve_renderbuffer_);
    if (gl().CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("incomplete resolve framebuffer for a " + size + " window");
    gl().BindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer_);
    gl().BindFramebuffer(GL_READ_FRAMEBUFFER, resolve_framebuffer_);
    width_ = w;
    height_ = h;
  }

  geometry::PixelRect clamp(geometry::PixelRect r) const {
    r.x0 = std::max(r.x0, 0);
    r.y0 = std::max(r.y0, 0);
    r.x1 = std::min(r.x1, width_);
    r.y1 = std::min(r.y1, height_);
    return r;
  }

  // Makes room for n more colours before the 24-bit counter would wrap.
  void reserve_colours(size_t n) {
    if (colour_ + n > kLastColour) clear_all();  // after 16.7 million primitives in one view
  }
  void use_colour(uint32_t c) {
    gl().Color4ub(GLubyte(c), GLubyte(c >> 8), GLubyte(c >> 16), 255);
  }

  // Clears the whole window (a fast path in Mesa, unlike a scissored clear) and restarts colours.
  void clear_all() {
    gl().Clear(GL_COLOR_BUFFER_BIT);
    gl().Finish();
    colour_ = 0;
  }

  // Reads the region back rectangle by rectangle and adds the pixels of `colour` (0xBBGGRR), or
  // with kAnyColour every pixel that is not black. The runs of several rectangles side by side
  // are put in (y, x) order before they join `lit`.
  void read_and_scan(const geometry::PixelRegion& region, uint32_t colour,
                     geometry::PixelSet& lit) {
    std::vector<geometry::PixelRect> rects;
    for (const geometry::PixelRect& r : region.rects)
      if (!clamp(r).empty()) rects.push_back(clamp(r));
    if (rects.size() == 1) return read_and_scan(rects.front(), colour, lit);
    geometry::PixelSet part;
    runs_.clear();
    for (const geometry::PixelRect& r : rects) {
      part.clear();
      read_and_scan(r, colour, part);
      runs_.insert(runs_.end(), part.runs().begin(), part.runs().end());
    }
    // A line's strip has rectangles side by side (rows interleave); a triangle's bands come in
    // row order already.
    append_in_order(runs_, lit);
  }

  // Reads one rectangle back (rows bottom-up, as GL window coordinates) and appends its pixels of
  // `colour` as runs.
  void read_and_scan(const geometry::PixelRect& r, uint32_t colour, geometry::PixelSet& lit) {
    if (r.empty()) return;
    const int w = r.x1 - r.x0, h = r.y1 - r.y0;
    readback_.resize(size_t(w) * h);
    gl().ReadPixels(r.x0, r.y0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, readback_.data());
    scan(r, colour == kAnyColour, colour, lit);
  }

  // Appends the runs of lit pixels of the read-back rectangle, row by row. A pixel is lit when
  // its RGB is not black (any_colour) or equals `colour`.
  void scan(const geometry::PixelRect& r, bool any_colour, uint32_t colour,
            geometry::PixelSet& lit) const {
    scan_rect(readback_.data(), size_t(r.x1 - r.x0), false, r, any_colour, colour, lit);
  }

  ReadbackMethod method_;
  std::vector<uint64_t> wild_pixel_indices_;
  std::string name_;  // the platform's name, for messages
  int samples_ = 0;   // PlatformSpec::samples; 0 = aliased
  // Multisample platforms: the resolve target, and resolved red value -> samples lit (255: invalid).
  GLuint resolve_framebuffer_ = 0, resolve_renderbuffer_ = 0;
  std::array<uint8_t, 256> decode_{};
  struct Covered {
    int32_t y, x;
    uint8_t k;
  };
  std::vector<Covered> covered_;
  geometry::Pixel wild_;
  std::unique_ptr<GlContext> context_;
  std::vector<uint32_t> readback_;
  std::vector<geometry::PixelRun> runs_;
  GLuint framebuffer_ = 0, renderbuffer_ = 0;
  GLint max_size_ = 0;
  bool warmed_up_ = false;  // warm_up() has run
  int width_ = 0, height_ = 0;
  uint32_t colour_ = 0;  // of the last primitive drawn; 0 (black) = none since the last clear
  DriverInfo info_;
  GLuint query_ = 0;
};

}  // namespace

std::unique_ptr<Platform> create_gl_platform(const PlatformSpec& spec, ReadbackMethod method,
                                                 std::vector<uint64_t> wild_pixel_indices) {
  return std::make_unique<GlPlatform>(spec, method, std::move(wild_pixel_indices));
}

}  // namespace ra::platforms
