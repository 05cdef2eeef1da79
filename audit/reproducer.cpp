// A record as a standalone C program (see the header).
#include "audit/reproducer.h"

#include <cctype>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>

#include "audit/audit_report.h"
#include "geometry/primitive.h"
#include "geometry/reference_rasterizer.h"
#include "metrics/records.h"
#include "rundir/build_record.h"
#include "rundir/experiment.h"
#include "rundir/records_reader.h"
#include "rundir/run_experiment.h"
#include "rundir/run_folder.h"
#include "rundir/shard.h"
#include "util/errors.h"
#include "rundir/shard_records.h"
#include "util/shell_quote.h"

namespace fs = std::filesystem;

namespace ra::audit {
namespace {

std::string hex(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%a", v);
  return buf;
}

std::string matrix(const geometry::Mat4& m) {
  std::string s;
  for (int i = 0; i < 16; ++i) s += (i ? (i % 4 ? ", " : ",\n    ") : "") + hex(m.m[i]);
  return s;
}

// The C program; @NAME@ placeholders are filled in by make_reproducer.
constexpr const char* kTemplate = R"(/* @TITLE@
 *
 * Draws one primitive as renderaudit's worker did and compares its pixels with the exact
 * reference rasterizer's (GL rasterization rules, no subpixel snapping).
 *   build: @BUILD@
 *   run:   @RUN@
 * Prints the pixels lit and their hash (FNV-1a 64 over each row's runs: y, x_begin, x_end as
 * 32-bit little-endian integers), then the worker's and the reference's, and a verdict. The
 * run's verdict of the worker's pixels: @WORKER_VERDICT_TEXT@; other pixels are not judged here.
 * Exit 0: the pixels are the reference's, or the worker's and GL allows them; 1: they are the
 * worker's and break GL's rules; 3: they are neither (drawn otherwise than the run drew it:
 * another driver or build), not judged; 2: EGL or GL failed. */
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <GL/glext.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

enum { W = @W@, H = @H@ };
static const double projection[16] = {   /* GL_PROJECTION, column-major */
    @PROJECTION@};
static const double modelview[16] = {    /* GL_MODELVIEW, column-major */
    @MODELVIEW@};
static const GLenum mode = @MODE@;
static const int vertex_count = @COUNT@;
static const double vertices[3][3] = {@VERTICES@};  /* object = world coordinates */
static const uint64_t worker_pixels = @RECORD_PIXELS@u, worker_hash = @RECORD_HASH@u;
static const uint64_t reference_pixels = @REF_PIXELS@u, reference_hash = @REF_HASH@u;
/* the run's verdict of the worker's pixels: 0 allowed by GL, 1 a violation, 3 not judged */
static const int worker_verdict = @WORKER_VERDICT@;
static const char worker_verdict_text[] = "@WORKER_VERDICT_TEXT@";

static uint64_t mix(uint64_t h, int32_t value) {
  uint32_t v = (uint32_t)value;
  for (int b = 0; b < 4; ++b) h = (h ^ ((v >> (8 * b)) & 0xffu)) * 0x100000001b3ull;
  return h;
}

int main(void) {
  PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
      (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
  EGLDisplay dpy = get_display ? get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL)
                               : EGL_NO_DISPLAY;
  EGLint major, minor;
  if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, &major, &minor) || !eglBindAPI(EGL_OPENGL_API)) {
    fprintf(stderr, "no surfaceless EGL display (EGL error 0x%x)\n", eglGetError());
    return 2;
  }
  EGLContext ctx = eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, NULL);
  if (ctx == EGL_NO_CONTEXT || !eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
    fprintf(stderr, "no desktop GL context (EGL error 0x%x)\n", eglGetError());
    return 2;
  }
  PFNGLGENFRAMEBUFFERSPROC gen_fb = (PFNGLGENFRAMEBUFFERSPROC)eglGetProcAddress("glGenFramebuffers");
  PFNGLBINDFRAMEBUFFERPROC bind_fb = (PFNGLBINDFRAMEBUFFERPROC)eglGetProcAddress("glBindFramebuffer");
  PFNGLGENRENDERBUFFERSPROC gen_rb = (PFNGLGENRENDERBUFFERSPROC)eglGetProcAddress("glGenRenderbuffers");
  PFNGLBINDRENDERBUFFERPROC bind_rb = (PFNGLBINDRENDERBUFFERPROC)eglGetProcAddress("glBindRenderbuffer");
  PFNGLRENDERBUFFERSTORAGEPROC storage =
      (PFNGLRENDERBUFFERSTORAGEPROC)eglGetProcAddress("glRenderbufferStorage");
  PFNGLFRAMEBUFFERRENDERBUFFERPROC attach =
      (PFNGLFRAMEBUFFERRENDERBUFFERPROC)eglGetProcAddress("glFramebufferRenderbuffer");
  GLuint fb, rb;
  gen_fb(1, &fb);
  bind_fb(GL_FRAMEBUFFER, fb);
  gen_rb(1, &rb);
  bind_rb(GL_RENDERBUFFER, rb);
  storage(GL_RENDERBUFFER, GL_RGBA8, W, H);
  attach(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
  printf("GL_RENDERER %s\nGL_VERSION  %s\n", glGetString(GL_RENDERER), glGetString(GL_VERSION));

  /* the worker's state: white on black, size and width 1, nothing smoothed, blended or culled */
  GLenum off[] = {GL_DEPTH_TEST, GL_LIGHTING, GL_DITHER, GL_POINT_SMOOTH, GL_LINE_SMOOTH,
                  GL_POLYGON_SMOOTH, GL_MULTISAMPLE, GL_CULL_FACE, GL_BLEND, GL_SCISSOR_TEST};
  for (unsigned i = 0; i < sizeof off / sizeof off[0]; ++i) glDisable(off[i]);
  glPointSize(1);
  glLineWidth(1);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  glViewport(0, 0, W, H);
  glMatrixMode(GL_PROJECTION);
  glLoadMatrixd(projection);
  glMatrixMode(GL_MODELVIEW);
  glLoadMatrixd(modelview);
  glClearColor(0, 0, 0, 0);
  glClear(GL_COLOR_BUFFER_BIT);
  glColor4f(1, 1, 1, 1);
  glBegin(mode);
  for (int i = 0; i < vertex_count; ++i) glVertex3d(vertices[i][0], vertices[i][1], vertices[i][2]);
  glEnd();
  glFinish();

  unsigned char *rgba = malloc((size_t)W * H * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, rgba);  /* row 0 = window y 0 (bottom) */
  uint64_t lit = 0, hash = 0xcbf29ce484222325ull;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W;) {
      const unsigned char *p = rgba + ((size_t)y * W + x) * 4;
      if (!(p[0] | p[1] | p[2] | p[3])) { ++x; continue; }
      int end = x;
      while (end < W && (rgba[((size_t)y * W + end) * 4] | rgba[((size_t)y * W + end) * 4 + 1] |
                         rgba[((size_t)y * W + end) * 4 + 2] | rgba[((size_t)y * W + end) * 4 + 3]))
        ++end;
      hash = mix(mix(mix(hash, y), x), end);
      lit += (uint64_t)(end - x);
      x = end;
    }
  printf("pixels lit  %llu (hash %llu)\n", (unsigned long long)lit, (unsigned long long)hash);
  printf("worker      %llu (hash %llu)\n", (unsigned long long)worker_pixels,
         (unsigned long long)worker_hash);
  printf("reference   %llu (hash %llu)\n", (unsigned long long)reference_pixels,
         (unsigned long long)reference_hash);
  free(rgba);
  if (lit == reference_pixels && hash == reference_hash) {
    printf("verdict     the reference's pixels\n");
    return 0;
  }
  if (lit == worker_pixels && hash == worker_hash) {
    printf("verdict     the worker's pixels: %s\n", worker_verdict_text);
    return worker_verdict;
  }
  printf("verdict     neither the worker's nor the reference's pixels: drawn otherwise than\n"
         "            the run drew it (another driver or build?); not judged here (renderaudit\n"
         "            show draws it with a platform and judges it)\n");
  return 3;
}
)";

void fill(std::string& s, const std::string& key, const std::string& value) {
  for (std::size_t at; (at = s.find("@" + key + "@")) != std::string::npos;)
    s.replace(at, key.size() + 2, value);
}

// Text safe inside the generated C file's /* ... */ comment: no comment end, no line break, no
// other control character (a path or a name from the command line or the run reaches it).
std::string comment_safe(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7f) {
      out += '?';
    } else if (c == '*' && i + 1 < text.size() && text[i + 1] == '/') {
      out += "* ";
    } else {
      out += char(c);
    }
  }
  return out;
}

// Text safe inside the generated C file's string literals and comments: a verdict's words and
// rule names are letters, digits, blanks and "+-():,'"; anything else (a hostile records file) is
// dropped.
std::string literal_safe(const std::string& text) {
  std::string out;
  for (const char c : text)
    if (std::isalnum(static_cast<unsigned char>(c)) || (c && std::strchr(" +-():,'", c))) out += c;
  return out;
}

}  // namespace

ReproducerVerdict reproducer_verdict(metrics::Conformance conformance,
                                     const std::string& violated_rules) {
  switch (conformance) {
    case metrics::Conformance::kExact:
      return {kReproducerAllowed, "exact (the reference's)"};
    case metrics::Conformance::kSnapped:
    case metrics::Conformance::kWithinSpec:
      return {kReproducerAllowed, std::string("allowed by GL (") +
                                      metrics::conformance_name(conformance) + ")"};
    case metrics::Conformance::kViolation:
      return {kReproducerViolation, "breaking GL's rules (" +
                                        (violated_rules.empty() ? "violation" : violated_rules) +
                                        ")"};
    case metrics::Conformance::kNotCompared:
      break;
  }
  return {kReproducerNotJudged, "not judged against GL's rules by the run"};
}

std::string reproducer_program(const std::string& c_file_name) {
  fs::path program = fs::path(c_file_name).replace_extension();
  if (program == fs::path(c_file_name)) program += ".out";  // a C file named without .c
  return program.string();
}

std::string reproducer_environment(const std::string& build_dir, const std::string& mesa_driver) {
  std::string env;
  if (!build_dir.empty()) {
    const std::string lib = rundir::build_library_dir(build_dir);
    env = "LD_LIBRARY_PATH=" + util::shell_quote(lib) + " ";
    std::error_code ec;
    if (fs::is_directory(lib + "/dri", ec)) env += "LIBGL_DRIVERS_PATH=" + util::shell_quote(lib + "/dri") + " ";
  }
  return env + "LIBGL_ALWAYS_SOFTWARE=1 GALLIUM_DRIVER=" + util::shell_quote(mesa_driver) + " LP_NUM_THREADS=0";
}

Reproducer make_reproducer(const ReproduceRequest& q, const std::string& c_file_name) {
  const std::string toml = rundir::run_folder::experiment(q.run_dir);
  if (!fs::is_regular_file(toml))
    throw util::UserError(q.run_dir + ": not a run directory (no experiment.toml)");
  const rundir::Experiment exp = rundir::load_run_experiment(q.run_dir);
  const rundir::PlatformSpec spec = rundir::experiment_platform(exp, q.platform);
  if (!spec.draws_with_gl() || spec.samples > 0 || spec.backend == rundir::Backend::kEglDevice)
    throw util::UserError(
        "reproduce draws through Mesa's surfaceless EGL: --platform must be one of "
        "osmesa-llvmpipe, osmesa-softpipe, egl-llvmpipe, egl-softpipe (or one of "
        "their builds), not '" +
        q.platform + "'");
  geometry::Kind kind;
  if (!geometry::parse_kind(q.kind, &kind))
    throw util::UserError("unknown kind '" + q.kind + "' (allowed: point, line, triangle)");
  const geometry::View* view = nullptr;
  for (const geometry::View& v : exp.views)
    if (v.id == q.view) view = &v;
  if (!view) throw util::UserError("the run has no view " + std::to_string(q.view));
  // The worker's record of it.
  std::optional<metrics::Record> record;
  for (const rundir::Shard& s : rundir::plan_shards(exp)) {
    if (s.platform != q.platform || s.kind != kind || s.view != q.view || q.index < s.begin ||
        q.index >= s.end)
      continue;
    const std::string path = rundir::trusted_records_path(q.run_dir, s);
    if (path.empty())
      throw util::UserError(s.records_path(q.run_dir) +
                            ": missing: the run has no record of this primitive");
    rundir::read_records(path, [&](const metrics::Record& r) {
      if (r.index == q.index) record = r;
    });
  }
  if (!record)
    throw util::UserError("the run has no record of " + q.platform + " " + q.kind + " " +
                          std::to_string(q.index) + " in view " + std::to_string(q.view));

  const geometry::Primitive prim = geometry::make_primitive(exp.seed, kind, q.index);
  const geometry::PixelSet reference = geometry::rasterize_reference(*view, prim);
  Reproducer out;
  out.record_pixels = record->pixels;
  out.record_hash = record->pixel_hash;
  out.violated_rules = record->violated_rules;
  out.view_text = "FOV " + std::to_string(int(std::lround(view->fov_deg))) + " deg, " +
                  std::to_string(view->width) + " x " + std::to_string(view->height);
  out.reference_pixels = reference.size();
  out.reference_hash = geometry::pixel_set_hash(reference);
  // The program is built beside its C file, wherever the commands are pasted.
  out.program = reproducer_program(c_file_name);
  out.build_line = "cc " + util::shell_quote(c_file_name) + " -o " +
                   util::shell_quote(out.program) + " -lEGL -lOpenGL";
  const std::string run = fs::path(out.program).has_parent_path() ? out.program
                                                                   : "./" + out.program;
  out.run_line = reproducer_environment(spec.build.empty() ? "" : spec.build_dir,
                                        spec.mesa_driver) +
                 " " + util::shell_quote(run);
  out.verdict = reproducer_verdict(record->conformance, record->violated_rules);

  std::string s = kTemplate;
  std::string vertices;
  for (int i = 0; i < geometry::vertex_count(kind); ++i)
    vertices += std::string(i ? ", " : "") + "{" + hex(prim.v[i].x) + ", " + hex(prim.v[i].y) +
                ", " + hex(prim.v[i].z) + "}";
  static const char* modes[] = {"GL_POINTS", "GL_LINES", "GL_TRIANGLES"};
  fill(s, "TITLE", comment_safe("renderaudit reproducer: " + q.platform + " " + q.kind + " " +
                       std::to_string(q.index) + ", view " + std::to_string(q.view) + " (" +
                       std::to_string(view->width) + "x" + std::to_string(view->height) + ", FOV " +
                       std::to_string(int(view->fov_deg)) + " degrees) of experiment " + exp.name + ", seed " +
                       std::to_string(exp.seed)));
  fill(s, "BUILD", comment_safe(out.build_line));
  fill(s, "RUN", comment_safe(out.run_line));
  fill(s, "W", std::to_string(view->width));
  fill(s, "H", std::to_string(view->height));
  fill(s, "PROJECTION", matrix(view->projection));
  fill(s, "MODELVIEW", matrix(view->view_matrix));
  fill(s, "MODE", modes[int(kind)]);
  fill(s, "COUNT", std::to_string(geometry::vertex_count(kind)));
  fill(s, "VERTICES", vertices);
  fill(s, "RECORD_PIXELS", std::to_string(out.record_pixels));
  fill(s, "RECORD_HASH", std::to_string(out.record_hash));
  fill(s, "REF_PIXELS", std::to_string(out.reference_pixels));
  fill(s, "REF_HASH", std::to_string(out.reference_hash));
  fill(s, "WORKER_VERDICT", std::to_string(out.verdict.exit_code));
  fill(s, "WORKER_VERDICT_TEXT", literal_safe(out.verdict.text));
  out.source = s;
  return out;
}

}  // namespace ra::audit
