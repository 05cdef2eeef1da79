// A GL driver as a RasterDevice (platforms/raster_device.h): every GL back end (OSMesa, Mesa's
// surfaceless EGL, an EGL device) through one context (platforms/gl_context.h), every GL call
// through its function table. The measurement itself is platforms/readback_measurement.cpp.
//
// Drawing goes to a framebuffer object of the view's size, never to a window-system buffer (EGL
// has none here; OSMesa's: glFinish on it copies the whole window into the caller's memory, about
// 150 us at 907x907, 30x the cost of drawing one primitive); with an FBO only the pixels read back
// are copied, by glReadPixels. The occlusion count is GL_SAMPLES_PASSED; the wait is glFinish.
//
// Layers: one more FBO per layer, each with its own RGBA8 renderbuffer of the view's size, made
// as layer 0's is: the same storage, viewport and state, so a primitive rasterizes to the same
// pixels in any layer. draw_each() binds each primitive's layer, brackets it with its own
// GL_SAMPLES_PASSED query (and, timed, a GL_TIME_ELAPSED query), and calls glFinish once. A
// layered window reads back through a pixel pack buffer: every rectangle's glReadPixels queued
// into it, one map for them all, where each glReadPixels into client memory would wait for the
// device (a batch's line strips are hundreds of rectangles); the pixels are scanned in the mapped
// buffer, which stays mapped until the next read.
//
// The scan on the device (scan(), platforms/gl_lit_mask.h; GL 4.3): the rectangles' glReadPixels
// go into a buffer that stays on the device, and a compute shader leaves a bit per pixel.
//
// Multisample platforms: the primitive is drawn into a multisample FBO (GL_RGBA8, `samples` samples
// per pixel, GL_MULTISAMPLE enabled) and resolved (glBlitFramebuffer) into a single-sample FBO that
// glReadPixels reads. Sample positions (llvmpipe 4x, from glGetMultisamplefv): (0.375, 0.125),
// (0.875, 0.375), (0.125, 0.625), (0.625, 0.875).
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "platforms/gl_context.h"
#include "platforms/gl_lit_mask.h"
#include "platforms/lit_mask.h"
#include "platforms/raster_device.h"

namespace ra::platforms {
namespace {

// Whether a GL_RENDERER names one of Mesa's CPU rasterizers: llvmpipe, softpipe, swrast, or zink
// on lavapipe ("zink (llvmpipe (LLVM 15.0.6, 256 bits))"), whose timer sees only part of the work.
bool draws_on_cpu(const std::string& renderer) {
  const std::string zink = "zink (";
  const std::string r = renderer.rfind(zink, 0) == 0 ? renderer.substr(zink.size()) : renderer;
  return r.rfind("llvmpipe", 0) == 0 || r.rfind("softpipe", 0) == 0 ||
         r.rfind("Software Rasterizer", 0) == 0;
}

class GlDevice : public RasterDevice {
 public:
  GlDevice(const rundir::PlatformSpec& spec, int max_layers)
      : name_(spec.name), samples_(spec.samples), max_layers_(max_layers) {
    context_ = create_gl_context(spec);  // sets Mesa's environment and checks the driver
    info_.backend = context_->backend();
    gl().GenFramebuffers(1, &framebuffer_);
    gl().BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    layer_framebuffers_ = {framebuffer_};
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
    const std::string renderer = info_.renderer;
    draws_on_host_ = draws_on_cpu(renderer);
    int major = 0, minor = 0;  // GL_VERSION begins "major.minor"
    std::sscanf(info_.version.c_str(), "%d.%d", &major, &minor);
    if (gl().has_compute() && (major > 4 || (major == 4 && minor >= 3)))
      glsl_for_scan_ = major > 4 || minor >= 5 ? 450 : 430;

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

  // The scan's GL objects go with this context, whichever is current now.
  ~GlDevice() override {
    if (!lit_mask_) return;
    context_->make_current();
    lit_mask_.reset();
  }

  DriverInfo info() const override { return info_; }

  // Several platforms in one process (tests: an aliased and a multisample one side by side) each
  // have their own context; GL calls go to the current one.
  void bind() override { context_->make_current(); }

  void set_view(const geometry::View& view) override {
    if (view.width != width_ || view.height != height_) resize(view.width, view.height);
    gl().Viewport(0, 0, width_, height_);
    if (!warmed_up_) warm_up();
    gl().MatrixMode(GL_PROJECTION);
    gl().LoadMatrixd(view.projection.m.data());
    gl().MatrixMode(GL_MODELVIEW);
    gl().LoadMatrixd(view.view_matrix.m.data());
  }
  int width() const override { return width_; }
  int height() const override { return height_; }

  double draw(const std::vector<geometry::Primitive>& prims, const std::vector<uint32_t>& colours,
              bool counted, const geometry::Pixel* wild,
              const std::vector<geometry::PixelRect>* resolve_rects = nullptr) override {
    const auto t0 = std::chrono::steady_clock::now();
    if (counted) gl().BeginQuery(GL_SAMPLES_PASSED, query_);
    for (size_t i = 0; i < prims.size(); ++i) {
      use_colour(colours[i]);
      draw_primitive(prims[i]);
    }
    if (wild) {
      use_colour(colours.front());
      draw_wild_pixel(*wild);
    }
    if (counted) gl().EndQuery(GL_SAMPLES_PASSED);
    if (resolve_rects) resolve(*resolve_rects);
    gl().Finish();
    return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  }

  uint64_t counted_fragments() override {
    GLuint n = 0;
    gl().GetQueryObjectuiv(query_, GL_QUERY_RESULT, &n);
    return n;
  }

  int layers() const override { return int(layer_framebuffers_.size()); }

  double draw_each(const std::vector<geometry::Primitive>& prims,
                   const std::vector<uint32_t>& colours, const std::vector<int>& layers,
                   bool timed) override {
    grow_queries(prims.size(), timed);
    timed_ = timed;
    const auto t0 = std::chrono::steady_clock::now();
    int bound = 0;
    for (size_t i = 0; i < prims.size(); ++i) {
      if (layers[i] != bound) {
        bound = layers[i];
        gl().BindFramebuffer(GL_FRAMEBUFFER, layer_framebuffers_[size_t(bound)]);
      }
      if (timed) gl().BeginQuery(GL_TIME_ELAPSED, time_queries_[i]);
      gl().BeginQuery(GL_SAMPLES_PASSED, count_queries_[i]);
      use_colour(colours[i]);
      draw_primitive(prims[i]);
      gl().EndQuery(GL_SAMPLES_PASSED);
      if (timed) gl().EndQuery(GL_TIME_ELAPSED);
    }
    if (bound != 0) gl().BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    gl().Finish();
    return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  }

  uint64_t fragments_of(size_t i) override {
    GLuint n = 0;
    gl().GetQueryObjectuiv(count_queries_.at(i), GL_QUERY_RESULT, &n);
    return n;
  }

  double device_us_of(size_t i) override {
    if (!timed_) return std::numeric_limits<double>::quiet_NaN();
    GLuint64 ns = 0;
    gl().GetQueryObjectui64v(time_queries_.at(i), GL_QUERY_RESULT, &ns);
    return double(ns) / 1e3;
  }

  bool device_clock() const override { return info_.timer_query && !draws_on_host_; }

  // Blits the rectangles from the multisample FBO into the resolve FBO (same place).
  void resolve(const std::vector<geometry::PixelRect>& rects) override {
    gl().BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
    gl().BindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_framebuffer_);
    for (const geometry::PixelRect& r : rects)
      gl().BlitFramebuffer(r.x0, r.y0, r.x1, r.y1, r.x0, r.y0, r.x1, r.y1, GL_COLOR_BUFFER_BIT,
                           GL_NEAREST);
    // Steady state: draw (and clear) into the multisample FBO, read from the resolved one.
    gl().BindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer_);
    gl().BindFramebuffer(GL_READ_FRAMEBUFFER, resolve_framebuffer_);
  }

  // glReadPixels of each rectangle (rows bottom-up, as GL window coordinates) into one buffer:
  // client memory, or, on a layered window, the pixel pack buffer, left mapped and scanned where
  // it lies (no copy) until the next read.
  void read(const std::vector<geometry::PixelRect>& rects, const std::vector<int>& layers) override {
    const size_t total = pack_offsets(rects);
    unmap_pack_buffer();
    const bool packed = layer_framebuffers_.size() > 1 && total > 0;
    if (!packed) {
      readback_.resize(total);
      read_pixels(rects, layers, readback_.data());
      return;
    }
    if (!pack_buffer_) gl().GenBuffers(1, &pack_buffer_);
    gl().BindBuffer(GL_PIXEL_PACK_BUFFER, pack_buffer_);
    if (total > pack_capacity_) {
      pack_capacity_ = std::max<size_t>(total, size_t(1) << 18);
      gl().BufferData(GL_PIXEL_PACK_BUFFER, GLsizeiptr(pack_capacity_ * 4), nullptr,
                      GL_STREAM_READ);
    }
    read_pixels(rects, layers, nullptr);
    packed_pixels_ = static_cast<const uint32_t*>(
        gl().MapBufferRange(GL_PIXEL_PACK_BUFFER, 0, GLsizeiptr(total * 4), GL_MAP_READ_BIT));
    gl().BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    if (!packed_pixels_) throw std::runtime_error("platform " + name_ + ": glMapBufferRange failed");
  }
  const uint32_t* pixels(size_t i) const override {
    return (packed_pixels_ ? packed_pixels_ : readback_.data()) + offsets_[i];
  }
  bool rows_top_down() const override { return false; }

  bool scans() const override { return samples_ == 0 && glsl_for_scan_ > 0; }

  // The rectangles read into the scan's buffer on the device, and the pass.
  void scan(const std::vector<geometry::PixelRect>& rects, const std::vector<int>& layers,
            const std::vector<uint32_t>& colours) override {
    if (!scans()) RasterDevice::scan(rects, layers, colours);
    if (!lit_mask_) lit_mask_ = std::make_unique<GlLitMask>(gl(), glsl_for_scan_, name_);
    scan_layout_ = lay_out_lit_masks(rects, colours);
    if (rects.empty()) return;
    pack_offsets(rects);
    unmap_pack_buffer();  // pixels() is over: a scan replaces the last read
    gl().BindBuffer(GL_PIXEL_PACK_BUFFER, lit_mask_->prepare(scan_layout_));
    read_pixels(rects, layers, nullptr);
    gl().BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    lit_mask_->run(scan_layout_);
  }
  const uint32_t* mask(size_t i) const override { return lit_mask_->mask(scan_layout_, i); }
  uint64_t lit_count(size_t i) const override { return lit_mask_->count(i); }

  // A whole-window clear is a fast path in Mesa, unlike a scissored one.
  void clear() override {
    for (size_t k = 1; k < layer_framebuffers_.size(); ++k) {
      gl().BindFramebuffer(GL_FRAMEBUFFER, layer_framebuffers_[k]);
      gl().Clear(GL_COLOR_BUFFER_BIT);
    }
    if (layer_framebuffers_.size() > 1) gl().BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    gl().Clear(GL_COLOR_BUFFER_BIT);
    gl().Finish();
  }

  size_t max_batch() const override { return std::numeric_limits<size_t>::max(); }

  // GL_TIME_ELAPSED against the CPU clock over the same draws: 8 rounds of 16 window-filling
  // quads at 256 x 256, each round between two glFinish; the median of the rounds' ratios. Near 1
  // where the timer measures what the CPU waits for (llvmpipe times its own rasterization on the
  // CPU); a GPU that runs while the CPU submits shows less. Leaves the window at 256 x 256 and the
  // matrices at identity: set_view() sets all of it again.
  double timer_over_cpu() override {
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
    clear();
    if (ratios.empty()) return std::numeric_limits<double>::quiet_NaN();
    std::sort(ratios.begin(), ratios.end());
    return 0.5 * (ratios[(ratios.size() - 1) / 2] + ratios[ratios.size() / 2]);
  }

 private:
  static constexpr double kQuad[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};  // NDC corners
  const GlApi& gl() const { return context_->gl(); }

  // Ends the last read's mapping of the pixel pack buffer (before it is written again).
  void unmap_pack_buffer() {
    if (!packed_pixels_) return;
    gl().BindBuffer(GL_PIXEL_PACK_BUFFER, pack_buffer_);
    gl().UnmapBuffer(GL_PIXEL_PACK_BUFFER);
    gl().BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    packed_pixels_ = nullptr;
  }

  // Where each rectangle starts when they are packed one after another (offsets_); returns their
  // pixels in all.
  size_t pack_offsets(const std::vector<geometry::PixelRect>& rects) {
    offsets_.clear();
    size_t total = 0;
    for (const geometry::PixelRect& r : rects) {
      offsets_.push_back(total);
      total += size_t(r.x1 - r.x0) * size_t(r.y1 - r.y0);
    }
    return total;
  }

  // glReadPixels of rectangle i from its layer to offsets_[i] of `to`, or of the bound pixel
  // pack buffer when `to` is null.
  void read_pixels(const std::vector<geometry::PixelRect>& rects, const std::vector<int>& layers,
                   uint32_t* to) {
    int bound = 0;
    for (size_t i = 0; i < rects.size(); ++i) {
      const geometry::PixelRect& r = rects[i];
      const int layer = layers.empty() ? 0 : layers[i];
      if (layer != bound) {
        bound = layer;
        gl().BindFramebuffer(GL_READ_FRAMEBUFFER, layer_framebuffers_[size_t(layer)]);
      }
      void* at = to ? static_cast<void*>(to + offsets_[i]) : reinterpret_cast<void*>(offsets_[i] * 4);
      gl().ReadPixels(r.x0, r.y0, r.x1 - r.x0, r.y1 - r.y0, GL_RGBA, GL_UNSIGNED_BYTE, at);
    }
    if (bound != 0) gl().BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
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
  }

  // At least n occlusion queries (and n timer queries when `timed`) for draw_each().
  void grow_queries(size_t n, bool timed) {
    auto grow = [&](std::vector<GLuint>& queries) {
      if (queries.size() >= n) return;
      const size_t had = queries.size();
      queries.resize(n);
      gl().GenQueries(GLsizei(n - had), queries.data() + had);
    };
    grow(count_queries_);
    if (timed) grow(time_queries_);
  }

  void use_colour(uint32_t c) {  // 0xBBGGRR
    gl().Color4ub(GLubyte(c), GLubyte(c >> 8), GLubyte(c >> 16), 255);
  }

  void draw_primitive(const geometry::Primitive& prim) {
    static const GLenum modes[] = {GL_POINTS, GL_LINES, GL_TRIANGLES};
    gl().Begin(modes[int(prim.kind)]);
    for (int i = 0; i < geometry::vertex_count(prim.kind); ++i)
      gl().Vertex3d(prim.v[i].x, prim.v[i].y, prim.v[i].z);
    gl().End();
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

  // One small point, line and triangle drawn untimed before the first primitive: the driver
  // compiles its shaders for this state at the first draw (about 7 ms on llvmpipe), which would
  // otherwise land in the first primitive's render_us. The caller clears.
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
    if (!layer_renderbuffers_.empty()) {
      gl().DeleteRenderbuffers(GLsizei(layer_renderbuffers_.size()), layer_renderbuffers_.data());
      gl().DeleteFramebuffers(GLsizei(layer_framebuffers_.size() - 1),
                              layer_framebuffers_.data() + 1);
    }
    const int layers =
        max_layers_ == 0 && !device_clock() ? 1 : layers_for_window(w, h, max_layers_);
    layer_renderbuffers_.assign(size_t(layers), 0);
    layer_framebuffers_.assign(size_t(layers), framebuffer_);
    gl().GenRenderbuffers(layers, layer_renderbuffers_.data());
    if (layers > 1) gl().GenFramebuffers(layers - 1, layer_framebuffers_.data() + 1);
    for (int k = 0; k < layers; ++k) {  // layer 0 last: its FBO stays bound
      const size_t l = size_t(layers - 1 - k);
      gl().BindFramebuffer(GL_FRAMEBUFFER, layer_framebuffers_[l]);
      gl().BindRenderbuffer(GL_RENDERBUFFER, layer_renderbuffers_[l]);
      gl().RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
      gl().FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                                   layer_renderbuffers_[l]);
      if (gl().CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("incomplete framebuffer for a " + std::to_string(w) + "x" +
                                 std::to_string(h) + " window (layer " + std::to_string(l) + ")");
    }
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

  std::string name_;  // the platform's name, for messages
  int samples_ = 0;   // PlatformSpec::samples; 0 = aliased
  int max_layers_ = 0;  // create_gl_device's cap on layers_for_window (0: none)
  std::unique_ptr<GlContext> context_;
  DriverInfo info_;
  bool draws_on_host_ = false;  // a Mesa CPU rasterizer (draws_on_cpu of GL_RENDERER)
  // framebuffer_ is layer 0 (and, multisampled, the multisample FBO); renderbuffer_ its storage
  // on the multisample platforms, which have one layer.
  GLuint framebuffer_ = 0, renderbuffer_ = 0, query_ = 0;
  std::vector<GLuint> layer_framebuffers_, layer_renderbuffers_;  // per layer; [0] = framebuffer_
  std::vector<GLuint> count_queries_, time_queries_;  // draw_each's, per primitive
  GLuint pack_buffer_ = 0;    // a layered window's readback (GL_PIXEL_PACK_BUFFER)
  const uint32_t* packed_pixels_ = nullptr;  // pack_buffer_ mapped by the last read, or null
  size_t pack_capacity_ = 0;  // its size in pixels
  bool timed_ = false;                                // the last draw_each was timed
  // Multisample platforms: the resolve target.
  GLuint resolve_framebuffer_ = 0, resolve_renderbuffer_ = 0;
  GLint max_size_ = 0;
  bool warmed_up_ = false;  // warm_up() has run
  int width_ = 0, height_ = 0;
  std::vector<uint32_t> readback_;  // the last read(), rectangle after rectangle
  std::vector<size_t> offsets_;     // where each rectangle starts in readback_ (or a buffer)
  int glsl_for_scan_ = 0;  // the GLSL version the scan on the device compiles for; 0: none (< 4.3)
  std::unique_ptr<GlLitMask> lit_mask_;  // the scan on the device, made at its first use
  LitMaskLayout scan_layout_;            // of the last scan()
};

}  // namespace

std::unique_ptr<RasterDevice> create_gl_device(const rundir::PlatformSpec& spec, int max_layers) {
  return std::make_unique<GlDevice>(spec, max_layers);
}

}  // namespace ra::platforms
