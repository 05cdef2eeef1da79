// One primitive as a PNG: platform pixels, reference pixels and the ideal projection
// (primitive_image.h), drawn by pixel_picture.h.
#include "triage/primitive_image.h"

#include <OpenImageIO/imagebuf.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <system_error>
#include <utility>
#include <vector>

#include "geometry/clipping.h"
#include "geometry/reference_rasterizer.h"
#include "metrics/conformance.h"
#include "metrics/point_metrics.h"
#include "platforms/platform.h"
#include "platforms/renderer_check.h"
#include "rundir/experiment.h"
#include "rundir/run_experiment.h"
#include "rundir/run_folder.h"
#include "runner/case_measurement.h"
#include "runner/effective_subpixel.h"
#include "triage/image_legend.h"
#include "util/errors.h"
#include "util/gl_child_process.h"

namespace fs = std::filesystem;

namespace ra::triage {
namespace {

// Passes everything to the real platform and keeps the last rendering, so that the image shows
// the very pixels measure_case() measured.
class RecordingPlatform : public platforms::Platform {
 public:
  explicit RecordingPlatform(platforms::Platform& inner) : inner_(inner) {}
  platforms::DriverInfo driver_info() const override { return inner_.driver_info(); }
  double measure_timer_over_cpu() override { return inner_.measure_timer_over_cpu(); }
  void set_view(const geometry::View& view) override { inner_.set_view(view); }
  platforms::RenderResult render(const geometry::Primitive& prim,
                                 const geometry::PixelRegion& expected) override {
    last = inner_.render(prim, expected);
    return last;
  }
  platforms::RenderResult last;

 private:
  platforms::Platform& inner_;
};

// The ideal projection to outline, GL window coordinates (pixels), and the window pixels it
// touches plus the margin.
struct IdealShape {
  std::vector<geometry::Vec2> points;  // 1: a point (cross); 2: a segment; >= 3: a closed polygon
  geometry::PixelRect rect;
};

IdealShape ideal_shape(const geometry::View& view, const geometry::Primitive& prim) {
  IdealShape s;
  switch (prim.kind) {
    case geometry::Kind::kPoint: {
      const metrics::IdealPoint p = metrics::project_point(view, prim.v[0]);
      if (p.visible) s.points = {p.window};
      s.rect = metrics::point_region(view, p, kImageMargin);
      break;
    }
    case geometry::Kind::kLine: {
      const geometry::ClippedSegment c = geometry::clip_segment(view, prim.v[0], prim.v[1]);
      if (geometry::ideally_visible(c))
        s.points = c.status == geometry::ClipStatus::kDegenerate
                       ? std::vector<geometry::Vec2>{c.p0}
                       : std::vector<geometry::Vec2>{c.p0, c.p1};
      s.rect = geometry::bounding_rect(c, view.width, view.height, kImageMargin);
      break;
    }
    case geometry::Kind::kTriangle: {
      const geometry::ClippedPolygon c =
          geometry::clip_triangle(view, prim.v[0], prim.v[1], prim.v[2]);
      s.points = c.vertices;  // visible: the polygon; degenerate: its point or segment
      s.rect = geometry::bounding_rect(c, view.width, view.height, kImageMargin);
      break;
    }
  }
  return s;
}

geometry::PixelRect unite(const geometry::PixelRect& a, const geometry::PixelRect& b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

// The pixels of `s` grown by `margin`, clamped to the window.
geometry::PixelRect around(const geometry::PixelSet& s, int margin, int width, int height) {
  if (s.empty()) return {};
  geometry::PixelRect r{s.runs().front().x_begin, s.runs().front().y, s.runs().front().x_end,
                        s.runs().back().y + 1};
  for (const geometry::PixelRun& run : s.runs())
    r.x0 = std::min(r.x0, run.x_begin), r.x1 = std::max(r.x1, run.x_end);
  return {std::max(0, r.x0 - margin), std::max(0, r.y0 - margin), std::min(width, r.x1 + margin),
          std::min(height, r.y1 + margin)};
}

// A planned crash or hang of the faulty platform: said instead of drawn (it aborts or sleeps
// forever on these by design).
void check_planned_faults(const std::string& platform, const rundir::Experiment& exp,
                          uint64_t index) {
  if (platform != "faulty") return;
  for (const auto& [list, what] :
       {std::pair{&exp.faults.crash, "crash"}, std::pair{&exp.faults.hang, "hang"}})
    if (std::find(list->begin(), list->end(), index) != list->end())
      throw util::UserError("primitive " + std::to_string(index) + " is a planned " + what +
                            " of the faulty platform ([faults] " + what + " in " + exp.path + ")");
}

void check_request(const ShowRequest& q, const rundir::Experiment& exp, geometry::Kind kind) {
  if (q.view < 1 || q.view > int(exp.views.size()))
    throw util::UserError("view " + std::to_string(q.view) + " out of range (allowed: 1 to " +
                          std::to_string(exp.views.size()) + ": " + exp.path + " has " +
                          std::to_string(exp.views.size()) +
                          (exp.views.size() == 1 ? " view)" : " views)"));
  const uint64_t count = exp.counts[int(kind)];
  if (count == 0)
    throw util::UserError("index " + std::to_string(q.index) + " out of range: " + exp.path +
                          " has no " + geometry::kind_plural(kind) + " (primitives." +
                          geometry::kind_plural(kind) + " = 0)");
  if (q.index >= count)
    throw util::UserError("index " + std::to_string(q.index) + " out of range (allowed: 0 to " +
                          std::to_string(count - 1) + ": " + exp.path + " has " +
                          std::to_string(count) + " " + geometry::kind_plural(kind) + " per view)");
  if (q.scale < 0 || q.scale > kMaxImageScale)
    throw util::UserError("scale " + std::to_string(q.scale) + " out of range (allowed: 1 to " +
                          std::to_string(kMaxImageScale) + ")");
  if (q.against == q.platform)
    throw util::UserError("--against " + q.against +
                          " is the platform drawn: name another, e.g. its driver build");
  check_planned_faults(q.platform, exp, q.index);
  if (!q.against.empty()) check_planned_faults(q.against, exp, q.index);
}

// What one platform drew of a primitive, measured as the run's workers measure it.
struct Drawing {
  metrics::Record record;
  geometry::PixelSet lit, reference, violating;
  bool judged = false;  // against GL's rules (not the reference itself)
};

// Draws `prim` in `view` on `platform` in this process: the driver that made the run's records,
// or a clear stop (renderer_check.h), on the grid the run's workers measured (the same
// calibration: deterministic platforms agree).
Drawing draw_on(const std::string& run_dir, const rundir::Experiment& exp,
                const std::string& platform, const geometry::View& view,
                const geometry::Primitive& prim) {
  const rundir::PlatformSpec spec = rundir::experiment_platform(exp, platform);
  const std::unique_ptr<platforms::Platform> p =
      platforms::create_platform(spec, rundir::fault_plan_for(exp, spec));
  platforms::require_run_driver(run_dir, platform, p->driver_info());
  Drawing d;
  const bool is_reference = platform == "reference";
  const geometry::SubpixelGrid effective =
      is_reference ? geometry::SubpixelGrid{} : runner::measure_effective_subpixel(*p).grid;
  RecordingPlatform recorder(*p);
  recorder.set_view(view);
  runner::CaseComparison comparison(!is_reference, effective);
  comparison.line_rule = runner::line_rule_for(spec, p->driver_info());
  const bool rectangles = comparison.line_rule == runner::CaseComparison::LineRule::kRectangle;
  d.record = runner::measure_case(platform, recorder, view, prim, comparison);
  d.lit = recorder.last.lit;
  d.reference = geometry::rasterize_reference(view, prim);
  if (rectangles && prim.kind == geometry::Kind::kLine) {  // Vulkan's strict lines: the rectangle's
    const geometry::ClippedSegment segment = geometry::clip_segment(view, prim.v[0], prim.v[1]);
    d.reference.clear();
    if (segment.status == geometry::ClipStatus::kVisible) {
      const auto [a, b] = rectangle_ends(segment, metrics::near_clipped_vertices(view, prim));
      d.reference = geometry::rasterize_rectangle_segment(a, b, view.width, view.height);
    }
  }
  if (!is_reference)
    metrics::judge_primitive(view, prim, d.lit, effective, &d.violating, rectangles);
  // the reference is not judged against GL's rules (its record says exact: it is the reference)
  d.judged = !is_reference && d.record.conformance != metrics::Conformance::kNotCompared;
  return d;
}

// The pixels `against` lit of `prim`, drawn in a child process (one Mesa per process) before this
// one draws: the child's runs come back as JSON [[y, x_begin, x_end], ...].
geometry::PixelSet lit_elsewhere(const ShowRequest& q, const rundir::Experiment& exp,
                                 const geometry::View& view, const geometry::Primitive& prim) {
  nlohmann::json runs;
  try {
    runs = util::run_in_child(fs::temp_directory_path().string(),
                              "renderaudit-show-" + std::to_string(::getpid()), [&] {
                                const Drawing d = draw_on(q.run_dir, exp, q.against, view, prim);
                                nlohmann::json out = nlohmann::json::array();
                                for (const geometry::PixelRun& r : d.lit.runs())
                                  out.push_back({r.y, r.x_begin, r.x_end});
                                return out;
                              });
  } catch (const std::exception& e) {
    throw util::UserError("--against " + q.against + ": " + e.what());
  }
  geometry::PixelSet lit;
  for (const nlohmann::json& r : runs)
    lit.append_run(r.at(0).get<int32_t>(), r.at(1).get<int32_t>(), r.at(2).get<int32_t>());
  return lit;
}

// Writes the composed picture with its legend under it (what each colour means, with the counts
// of `out`) to the request's PNG, or RUN/show/P.K.vV.I.png; sets out.path and the image's size.
void write_picture(const ComposedPicture& picture, const ShowRequest& q, geometry::Kind kind,
                   bool judged, PrimitiveImage& out) {
  out.path = q.out_path.empty()
                 ? (fs::path(q.run_dir) / "show" /
                    (q.platform + "." + geometry::kind_name(kind) + ".v" + std::to_string(q.view) +
                     "." + std::to_string(q.index) + ".png"))
                       .string()
                 : q.out_path;
  std::string ext = fs::path(out.path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext != ".png") throw util::UserError(out.path + ": the image is a PNG: name a .png file");
  const fs::path parent = fs::path(out.path).parent_path();
  if (!parent.empty()) {
    std::error_code ec;
    fs::create_directories(parent, ec);
  }
  const std::vector<LegendEntry> legend =
      picture_legend(picture, q.platform, q.against, judged ? out.record.violating_pixels : -1);
  for (const LegendEntry& e : legend) out.legend.push_back(e.text);
  bool text_drawn = true;
  std::pair<int, int> inset_at;
  OIIO::ImageBuf image = with_legend(picture.main, picture.inset, legend, &text_drawn, &inset_at);
  if (!text_drawn)
    out.legend_note =
        "the legend's text needs the DejaVu Sans font (Debian: "
        "fonts-dejavu-core); its colour squares are drawn";
  out.inset_x = inset_at.first, out.inset_y = inset_at.second;
  out.image_width = image.spec().width;
  out.image_height = image.spec().height;
  image.specmod().attribute("Software", "renderaudit show");
  image.specmod().attribute(
      "ImageDescription",
      q.platform + " " + geometry::kind_name(kind) + " " + std::to_string(q.index) + ", view " +
          std::to_string(q.view) + " of " + q.run_dir +
          ": grey both, orange platform only, blue reference only (both allowed by GL), black a "
          "pixel GL forbids lit, hatched green one GL requires missing, ringed in magenta, red "
          "the ideal projection" +
          (q.against.empty() ? ""
                             : "; magenta squares in the inset: drawn otherwise by " + q.against));
  if (!image.write(out.path))
    throw util::UserError(out.path + ": cannot write the image: " + image.geterror());
}

}  // namespace

PrimitiveImage show_primitive(const ShowRequest& q) {
  const std::string toml = rundir::run_folder::experiment(q.run_dir);
  if (!fs::is_regular_file(toml))
    throw util::UserError(q.run_dir + ": not a run directory (no experiment.toml)");
  const rundir::Experiment exp = rundir::load_run_experiment(q.run_dir);
  // an unknown platform said first
  rundir::experiment_platform(exp, q.platform);
  if (!q.against.empty()) rundir::experiment_platform(exp, q.against);
  geometry::Kind kind;
  if (!geometry::parse_kind(q.kind, &kind))
    throw util::UserError("unknown kind '" + q.kind + "' (allowed: point, line, triangle)");
  check_request(q, exp, kind);

  PrimitiveImage out;
  for (const geometry::View& v : exp.views)
    if (v.id == q.view) out.view = v;
  const geometry::View& view = out.view;
  const geometry::Primitive prim = geometry::make_primitive(exp.seed, kind, q.index);

  // The other platform first, in a child, before this process makes a context of its own.
  PictureLayers layers;
  layers.window_width = view.width, layers.window_height = view.height;
  layers.has_other = !q.against.empty();
  if (layers.has_other) layers.other = lit_elsewhere(q, exp, view, prim);
  // Render once, measure that rendering, and rasterize the reference for comparison.
  Drawing d = draw_on(q.run_dir, exp, q.platform, view, prim);
  out.record = d.record;
  out.violating = d.violating.size();
  for (const geometry::Pixel& p : d.lit)
    (d.reference.contains(p) ? out.both : out.platform_only) += 1;
  for (const geometry::Pixel& p : d.reference)
    if (!d.lit.contains(p)) ++out.reference_only;

  // The window pixels shown: the same for both sides of a pair.
  const IdealShape ideal = ideal_shape(view, prim);
  const auto shown_with = [&](int margin) {
    geometry::PixelRect r = unite(around(d.lit, margin, view.width, view.height),
                                  around(d.reference, margin, view.width, view.height));
    r = unite(unite(r, around(layers.other, margin, view.width, view.height)), ideal.rect);
    if (r.empty() || (view.width <= kWholeWindowMax && view.height <= kWholeWindowMax))
      r = {0, 0, view.width, view.height};
    return r;
  };
  geometry::PixelRect shown = shown_with(kImageMargin);
  const auto scale_of = [&](const geometry::PixelRect& r) {
    return q.scale > 0 ? q.scale
                       : std::max(1, kTargetImageSize / std::max(r.x1 - r.x0, r.y1 - r.y0));
  };
  // room for the rings around what is drawn, at the scale it is drawn at (the same scale)
  const int reach = marker_ring_reach(
      scale_of(shown) * std::max(shown.x1 - shown.x0, shown.y1 - shown.y0), scale_of(shown));
  const int S = scale_of(shown);
  shown = shown_with(std::max(kImageMargin, (reach + S - 1) / S));
  out.shown = shown;
  const int cols = shown.x1 - shown.x0, rows = shown.y1 - shown.y0;
  if (int64_t(cols) * S > kMaxImageSide || int64_t(rows) * S > kMaxImageSide)
    throw util::UserError("the image would be " + std::to_string(int64_t(cols) * S) + " x " +
                          std::to_string(int64_t(rows) * S) + " px (at most " +
                          std::to_string(kMaxImageSide) + " per side): choose a smaller --scale");
  out.scale = S;
  out.width = cols * S;
  out.height = rows * S;

  layers.lit = std::move(d.lit);
  layers.reference = std::move(d.reference);
  layers.violating = std::move(d.violating);
  layers.ideal = ideal.points;
  out.picture = compose_picture(layers, shown, S);
  write_picture(out.picture, q, kind, d.judged, out);
  out.picture.main.rgb.clear();
  out.picture.inset.rgb.clear();
  return out;
}

}  // namespace ra::triage
