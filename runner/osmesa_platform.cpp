// Mesa's OSMesa (llvmpipe or softpipe) as a platform: no GPU and no display are needed.
//
// Drawing goes to a framebuffer object of the view's size, not to OSMesa's window-system buffer:
// glFinish on the latter copies the whole window into the caller's memory (about 150 us at
// 907x907 here, 30x the cost of drawing one primitive); with an FBO only the pixels read back are
// copied, by glReadPixels.
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
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "runner/platform.h"

namespace ra {
namespace {

constexpr uint32_t kRgb = 0x00ffffffu;  // RGB bytes of a little-endian RGBA8 pixel
constexpr uint32_t kAnyColour = 0xffffffffu;
constexpr uint32_t kLastColour = 0x00ffffffu;

class OsmesaPlatform : public Platform {
 public:
  OsmesaPlatform(const PlatformSpec& spec, ReadbackMethod method, std::vector<uint64_t> wild)
      : method_(method), wild_pixel_indices_(std::move(wild)) {
    // Mesa reads these when the first context is made; only validated names reach it.
    setenv("GALLIUM_DRIVER", spec.gallium_driver, 1);
    setenv("LP_NUM_THREADS", "0", 0);
    context_ = OSMesaCreateContextExt(OSMESA_RGBA, 0, 0, 0, nullptr);
    if (!context_) throw std::runtime_error(std::string("OSMesaCreateContextExt failed for ") + spec.name);
    // The window-system buffer is never drawn to; it only has to exist for MakeCurrent.
    if (!OSMesaMakeCurrent(context_, winsys_pixel_, GL_UNSIGNED_BYTE, 1, 1))
      throw std::runtime_error("OSMesaMakeCurrent failed");
    load(gen_framebuffers_, "glGenFramebuffers");
    load(bind_framebuffer_, "glBindFramebuffer");
    load(gen_renderbuffers_, "glGenRenderbuffers");
    load(delete_renderbuffers_, "glDeleteRenderbuffers");
    load(bind_renderbuffer_, "glBindRenderbuffer");
    load(renderbuffer_storage_, "glRenderbufferStorage");
    load(framebuffer_renderbuffer_, "glFramebufferRenderbuffer");
    load(check_framebuffer_, "glCheckFramebufferStatus");
    gen_framebuffers_(1, &framebuffer_);
    bind_framebuffer_(GL_FRAMEBUFFER, framebuffer_);
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size_);
    gen_queries_ = reinterpret_cast<PFNGLGENQUERIESPROC>(OSMesaGetProcAddress("glGenQueries"));
    begin_query_ = reinterpret_cast<PFNGLBEGINQUERYPROC>(OSMesaGetProcAddress("glBeginQuery"));
    end_query_ = reinterpret_cast<PFNGLENDQUERYPROC>(OSMesaGetProcAddress("glEndQuery"));
    get_query_ = reinterpret_cast<PFNGLGETQUERYOBJECTUIVPROC>(
        OSMesaGetProcAddress("glGetQueryObjectuiv"));
    if (!gen_queries_ || !begin_query_ || !end_query_ || !get_query_)
      throw std::runtime_error("OSMesa lacks occlusion queries (GL 1.5)");
    gen_queries_(1, &query_);

    const char* ext = reinterpret_cast<const char*>(glGetString(GL_EXTENSIONS));
    info_.renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    info_.version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    info_.vendor = reinterpret_cast<const char*>(glGetString(GL_VENDOR));
    GLint bits = 0;
    glGetIntegerv(GL_SUBPIXEL_BITS, &bits);
    info_.subpixel_bits = bits;
    info_.timer_query = ext && std::strstr(ext, "GL_ARB_timer_query");

    // The paper's conditions: white on black, size/width 1, no antialiasing, both faces filled.
    for (GLenum cap : {GL_DEPTH_TEST, GL_LIGHTING, GL_DITHER, GL_POINT_SMOOTH, GL_LINE_SMOOTH,
                       GL_POLYGON_SMOOTH, GL_MULTISAMPLE, GL_CULL_FACE, GL_BLEND, GL_SCISSOR_TEST})
      glDisable(cap);
    glPointSize(1);
    glLineWidth(1);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glClearColor(0, 0, 0, 0);
    glColor4f(1, 1, 1, 1);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
  }

  ~OsmesaPlatform() override { OSMesaDestroyContext(context_); }

  DriverInfo driver_info() const override { return info_; }

  void set_view(const View& view) override {
    if (view.width != width_ || view.height != height_) resize(view.width, view.height);
    glViewport(0, 0, width_, height_);
    glMatrixMode(GL_PROJECTION);
    glLoadMatrixd(view.projection.m.data());
    glMatrixMode(GL_MODELVIEW);
    glLoadMatrixd(view.view_matrix.m.data());
    clear_all();
  }

  RenderResult render(const Primitive& prim, const PixelRegion& expected) override {
    RenderResult out;
    switch (method_) {
      case ReadbackMethod::kDrawOnly:  // the floor: what the renderer itself must spend
        out.render_us = draw_and_finish(prim);
        return out;
      case ReadbackMethod::kFullWindow:  // the paper's method: clear, draw, read everything
        glClear(GL_COLOR_BUFFER_BIT);
        glFinish();  // keep the clear out of render_us
        out.render_us = draw_and_finish(prim);
        read_and_scan({0, 0, width_, height_}, kAnyColour, out.lit);
        out.full_scan = true;
        return out;
      case ReadbackMethod::kRegionWithProof:
        break;
    }
    reserve_colours(1);
    use_colour(++colour_);
    const Pixel* wild = wild_pixel_for(prim, expected);
    begin_query_(GL_SAMPLES_PASSED, query_);
    out.render_us = draw_and_finish(prim, true, wild);
    GLuint samples = 0;
    get_query_(query_, GL_QUERY_RESULT, &samples);

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
    glColor4ub(255, 255, 255, 255);
    begin_query_(GL_SAMPLES_PASSED, query_);
    out.render_us = draw_and_finish(prim, true, wild);
    get_query_(query_, GL_QUERY_RESULT, &samples);
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
  std::vector<RenderResult> render_batch(const std::vector<Primitive>& prims,
                                         const std::vector<PixelRegion>& expected) override {
    if (method_ == ReadbackMethod::kDrawOnly) return draw_batch_only(prims);
    if (method_ != ReadbackMethod::kRegionWithProof || prims.size() < 2)
      return Platform::render_batch(prims, expected);
    reserve_colours(prims.size());
    const uint32_t first = colour_ + 1;
    std::vector<RenderResult> out(prims.size());
    const auto t0 = std::chrono::steady_clock::now();
    begin_query_(GL_SAMPLES_PASSED, query_);
    for (size_t i = 0; i < prims.size(); ++i) {
      use_colour(++colour_);
      draw(prims[i], wild_pixel_for(prims[i], expected[i]));
    }
    end_query_(GL_SAMPLES_PASSED);
    glFinish();
    const double share_us =
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() /
        double(prims.size());
    GLuint samples = 0;
    get_query_(query_, GL_QUERY_RESULT, &samples);
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
  // Draws the primitive and waits for it; returns the CPU time in microseconds. With
  // `end_query`, the running occlusion query is ended right after the draw.
  double draw_and_finish(const Primitive& prim, bool end_query = false, const Pixel* wild = nullptr) {
    const auto t0 = std::chrono::steady_clock::now();
    draw(prim, wild);
    if (end_query) end_query_(GL_SAMPLES_PASSED);
    glFinish();
    return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  }

  void draw(const Primitive& prim, const Pixel* wild) {
    static const GLenum modes[] = {GL_POINTS, GL_LINES, GL_TRIANGLES};
    glBegin(modes[int(prim.kind)]);
    for (int i = 0; i < vertex_count(prim.kind); ++i) glVertex3d(prim.v[i].x, prim.v[i].y, prim.v[i].z);
    glEnd();
    if (wild) draw_wild_pixel(*wild);
  }

  // The batched floor (benchmark only): the batch drawn under one glFinish, nothing read back.
  std::vector<RenderResult> draw_batch_only(const std::vector<Primitive>& prims) {
    std::vector<RenderResult> out(prims.size());
    const auto t0 = std::chrono::steady_clock::now();
    for (const Primitive& prim : prims) draw(prim, nullptr);
    glFinish();
    const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    for (RenderResult& r : out) r.render_us = us / double(prims.size()), r.batch_size = int(prims.size());
    return out;
  }

  // Test-only fault: where the extra pixel goes (the quadrant opposite the expected region), or
  // nullptr when this primitive has none.
  const Pixel* wild_pixel_for(const Primitive& prim, const PixelRegion& region) {
    if (std::find(wild_pixel_indices_.begin(), wild_pixel_indices_.end(), prim.index) ==
        wild_pixel_indices_.end())
      return nullptr;
    const PixelRect expected = region.bounds();
    const int cx = expected.empty() ? 0 : (expected.x0 + expected.x1) / 2;
    const int cy = expected.empty() ? 0 : (expected.y0 + expected.y1) / 2;
    wild_ = {(cx + width_ / 2) % width_, (cy + height_ / 2) % height_};
    return &wild_;
  }

  // Lights pixel p through GL (so only the readback can find it): a point at its centre in NDC.
  void draw_wild_pixel(Pixel p) {
    glMatrixMode(GL_PROJECTION);
    glPushMatrix();
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
    glPushMatrix();
    glLoadIdentity();
    glBegin(GL_POINTS);
    glVertex2d(2.0 * (p.x + 0.5) / width_ - 1.0, 2.0 * (p.y + 0.5) / height_ - 1.0);
    glEnd();
    glPopMatrix();
    glMatrixMode(GL_PROJECTION);
    glPopMatrix();
    glMatrixMode(GL_MODELVIEW);
  }

  template <typename F>
  void load(F& fn, const char* name) {
    fn = reinterpret_cast<F>(OSMesaGetProcAddress(name));
    if (!fn) throw std::runtime_error(std::string("OSMesa lacks ") + name);
  }

  void resize(int w, int h) {
    if (w > max_size_ || h > max_size_)
      throw std::runtime_error("window " + std::to_string(w) + "x" + std::to_string(h) +
                               " exceeds this driver's GL_MAX_RENDERBUFFER_SIZE " +
                               std::to_string(max_size_));
    if (renderbuffer_) delete_renderbuffers_(1, &renderbuffer_);
    gen_renderbuffers_(1, &renderbuffer_);
    bind_renderbuffer_(GL_RENDERBUFFER, renderbuffer_);
    renderbuffer_storage_(GL_RENDERBUFFER, GL_RGBA8, w, h);
    framebuffer_renderbuffer_(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, renderbuffer_);
    if (check_framebuffer_(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("incomplete framebuffer for a " + std::to_string(w) + "x" +
                               std::to_string(h) + " window");
    width_ = w;
    height_ = h;
  }

  PixelRect clamp(PixelRect r) const {
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
    glColor4ub(GLubyte(c), GLubyte(c >> 8), GLubyte(c >> 16), 255);
  }

  // Clears the whole window (a fast path in Mesa, unlike a scissored clear) and restarts colours.
  void clear_all() {
    glClear(GL_COLOR_BUFFER_BIT);
    glFinish();
    colour_ = 0;
  }

  // Reads the region back rectangle by rectangle and adds the pixels of `colour` (0xBBGGRR), or
  // with kAnyColour every pixel that is not black. The runs of several rectangles side by side
  // are put in (y, x) order before they join `lit`.
  void read_and_scan(const PixelRegion& region, uint32_t colour, PixelSet& lit) {
    std::vector<PixelRect> rects;
    for (const PixelRect& r : region.rects)
      if (!clamp(r).empty()) rects.push_back(clamp(r));
    if (rects.size() == 1) return read_and_scan(rects.front(), colour, lit);
    PixelSet part;
    runs_.clear();
    for (const PixelRect& r : rects) {
      part.clear();
      read_and_scan(r, colour, part);
      runs_.insert(runs_.end(), part.runs().begin(), part.runs().end());
    }
    std::sort(runs_.begin(), runs_.end(), [](const PixelRun& a, const PixelRun& b) {
      return a.y != b.y ? a.y < b.y : a.x_begin < b.x_begin;
    });
    for (const PixelRun& run : runs_) lit.append_run(run.y, run.x_begin, run.x_end);
  }

  // Reads one rectangle back (rows bottom-up, as GL window coordinates) and appends its pixels of
  // `colour` as runs.
  void read_and_scan(const PixelRect& r, uint32_t colour, PixelSet& lit) {
    if (r.empty()) return;
    const int w = r.x1 - r.x0, h = r.y1 - r.y0;
    readback_.resize(size_t(w) * h);
    glReadPixels(r.x0, r.y0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, readback_.data());
    if (colour == kAnyColour) {
      scan(r, [](uint32_t v) { return (v & kRgb) != 0; }, lit);
    } else {
      scan(r, [colour](uint32_t v) { return (v & kRgb) == colour; }, lit);
    }
  }

  template <typename IsLit>
  void scan(const PixelRect& r, IsLit is_lit, PixelSet& lit) const {
    const int w = r.x1 - r.x0, h = r.y1 - r.y0;
    for (int y = 0; y < h; ++y) {
      const uint32_t* row = readback_.data() + size_t(y) * w;
      int x = 0;
      while (x < w) {
        while (x < w && !is_lit(row[x])) ++x;
        const int begin = x;
        while (x < w && is_lit(row[x])) ++x;
        lit.append_run(r.y0 + y, r.x0 + begin, r.x0 + x);
      }
    }
  }

  ReadbackMethod method_;
  std::vector<uint64_t> wild_pixel_indices_;
  Pixel wild_;
  OSMesaContext context_ = nullptr;
  uint8_t winsys_pixel_[4] = {};
  std::vector<uint32_t> readback_;
  std::vector<PixelRun> runs_;
  GLuint framebuffer_ = 0, renderbuffer_ = 0;
  GLint max_size_ = 0;
  PFNGLGENFRAMEBUFFERSPROC gen_framebuffers_ = nullptr;
  PFNGLBINDFRAMEBUFFERPROC bind_framebuffer_ = nullptr;
  PFNGLGENRENDERBUFFERSPROC gen_renderbuffers_ = nullptr;
  PFNGLDELETERENDERBUFFERSPROC delete_renderbuffers_ = nullptr;
  PFNGLBINDRENDERBUFFERPROC bind_renderbuffer_ = nullptr;
  PFNGLRENDERBUFFERSTORAGEPROC renderbuffer_storage_ = nullptr;
  PFNGLFRAMEBUFFERRENDERBUFFERPROC framebuffer_renderbuffer_ = nullptr;
  PFNGLCHECKFRAMEBUFFERSTATUSPROC check_framebuffer_ = nullptr;
  int width_ = 0, height_ = 0;
  uint32_t colour_ = 0;  // of the last primitive drawn; 0 (black) = none since the last clear
  DriverInfo info_;
  GLuint query_ = 0;
  PFNGLGENQUERIESPROC gen_queries_ = nullptr;
  PFNGLBEGINQUERYPROC begin_query_ = nullptr;
  PFNGLENDQUERYPROC end_query_ = nullptr;
  PFNGLGETQUERYOBJECTUIVPROC get_query_ = nullptr;
};

}  // namespace

std::unique_ptr<Platform> create_osmesa_platform(const PlatformSpec& spec, ReadbackMethod method,
                                                 std::vector<uint64_t> wild_pixel_indices) {
  return std::make_unique<OsmesaPlatform>(spec, method, std::move(wild_pixel_indices));
}

}  // namespace ra
