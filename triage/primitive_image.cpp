// One primitive as a PNG: platform pixels, reference pixels and the ideal projection
// (primitive_image.h).
#include "triage/primitive_image.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <system_error>
#include <utility>
#include <vector>

#include "rundir/run_folder.h"
#include "triage/image_legend.h"
#include "runner/case_measurement.h"
#include "metrics/conformance.h"
#include "runner/effective_subpixel.h"
#include "geometry/clipping.h"
#include "util/errors.h"
#include "rundir/experiment.h"
#include "rundir/run_experiment.h"
#include "platforms/platform.h"
#include "platforms/renderer_check.h"
#include "metrics/point_metrics.h"
#include "geometry/reference_rasterizer.h"

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

Rgb8 darker(Rgb8 c) { return {uint8_t(c.r * 4 / 5), uint8_t(c.g * 4 / 5), uint8_t(c.b * 4 / 5)}; }

// Clusters of marked points (image pixels): points in cells of side `join` that touch (8
// neighbours) are one cluster. Returns each cluster's bounding box {x0, y0, x1, y1} (inclusive)
// and its number of points.
struct Cluster {
  std::array<int, 4> box;
  int64_t points = 0;
};
std::vector<Cluster> clusters(const std::vector<std::pair<int, int>>& points, int join) {
  std::map<std::pair<int, int>, int> cell_of;  // cell -> index into `parent`
  std::vector<int> parent;
  const auto find = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (const auto& [x, y] : points) {
    const std::pair<int, int> c{x / join, y / join};
    if (!cell_of.count(c)) {
      cell_of[c] = int(parent.size());
      parent.push_back(int(parent.size()));
    }
  }
  for (const auto& [c, i] : cell_of)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const auto it = cell_of.find({c.first + dx, c.second + dy});
        if (it != cell_of.end()) parent[find(i)] = find(it->second);
      }
  std::map<int, Cluster> of_root;
  for (const auto& [x, y] : points) {
    const int root = find(cell_of[{x / join, y / join}]);
    auto [it, fresh] = of_root.try_emplace(root, Cluster{{x, y, x, y}, 0});
    auto& b = it->second.box;
    b = {std::min(b[0], x), std::min(b[1], y), std::max(b[2], x), std::max(b[3], y)};
    ++it->second.points;
  }
  std::vector<Cluster> out;
  for (const auto& [root, c] : of_root) out.push_back(c);
  return out;
}

// Draws the rings on rgb (width x height, blocks of `scale`): every halo first, then every ring,
// so that a halo never cuts a neighbouring ring. A ring never hides what a window pixel is: it
// leaves the centre of each block of 3 image pixels or more it crosses.
void draw_rings(std::vector<uint8_t>& rgb, int width, int height, int scale,
                const std::vector<MarkerRing>& rings) {
  for (const bool halo : {true, false})
    for (const MarkerRing& r : rings)
      for (int y = std::max(0, r.cy - r.radius - 4); y <= std::min(height - 1, r.cy + r.radius + 4); ++y)
        for (int x = std::max(0, r.cx - r.radius - 4); x <= std::min(width - 1, r.cx + r.radius + 4);
             ++x) {
          const double d = std::hypot(double(x - r.cx), double(y - r.cy)) - double(r.radius);
          const bool ring = std::fabs(d) <= r.half_width;
          const bool around = std::fabs(d) <= r.half_width + 1;
          if (halo ? !around : !ring) continue;
          if (scale >= 3 && x % scale == scale / 2 && y % scale == scale / 2) continue;
          const Rgb8 c = halo ? kUnlitColor : kMarkerColor;
          uint8_t* px = &rgb[(std::size_t(y) * width + x) * 3];
          px[0] = c.r, px[1] = c.g, px[2] = c.b;
        }
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
  if (q.platform == "faulty") {
    // The faulty platform aborts or sleeps forever on these by design: say so instead.
    for (const auto& [list, what] :
         {std::pair{&exp.faults.crash, "crash"}, std::pair{&exp.faults.hang, "hang"}})
      if (std::find(list->begin(), list->end(), q.index) != list->end())
        throw util::UserError("primitive " + std::to_string(q.index) + " is a planned " + what +
                              " of the faulty platform ([faults] " + what + " in " + exp.path +
                              ")");
  }
}

// Writes `picture` with its legend under it (what each colour means, with the counts of `out`) to
// the request's PNG, or RUN/show/P.K.vV.I.png; sets out.path and the image's size.
void write_picture(const OIIO::ImageBuf& buf, const ShowRequest& q, geometry::Kind kind,
                   PrimitiveImage& out) {
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
  // The legend under the picture: what each colour means and how many window pixels have it.
  // the reference is not judged against GL's rules (its record says exact: it is the reference)
  const bool judged = q.platform != "reference" &&
                      out.record.conformance != metrics::Conformance::kNotCompared;
  const std::vector<LegendEntry> legend =
      picture_legend(out.picture, q.platform, judged ? out.record.violating_pixels : -1);
  bool text_drawn = true;
  const OIIO::ImageBuf image = with_legend(buf, legend, &text_drawn);
  if (!text_drawn) out.legend_note = "the legend's text needs the DejaVu Sans font (Debian: "
                                     "fonts-dejavu-core); its colour squares are drawn";
  out.image_width = image.spec().width;
  out.image_height = image.spec().height;
  if (!image.write(out.path))
    throw util::UserError(out.path + ": cannot write the image: " + image.geterror());
}

}  // namespace

PixelPicture draw_pixel_picture(const geometry::PixelSet& lit, const geometry::PixelSet& reference,
                                const geometry::PixelSet& violating,
                                const geometry::PixelRect& shown, int S) {
  PixelPicture pic;
  const int cols = shown.x1 - shown.x0, rows = shown.y1 - shown.y0;
  pic.width = cols * S;
  pic.height = rows * S;
  // the colours' counts, whole window
  for (const geometry::Pixel& p : lit) {
    if (violating.contains(p)) ++pic.forbidden;
    else (reference.contains(p) ? pic.both : pic.platform_only) += 1;
  }
  for (const geometry::Pixel& p : reference)
    if (!lit.contains(p)) (violating.contains(p) ? pic.missing : pic.reference_only) += 1;
  for (const geometry::Pixel& p : violating)
    if (!lit.contains(p) && !reference.contains(p)) ++pic.missing;

  // Which rasterizer lit each shown pixel: bit 0 platform, bit 1 reference, bit 2 a rule's.
  std::vector<uint8_t> who(std::size_t(cols) * rows, 0);
  auto mark = [&](const geometry::PixelSet& s, uint8_t bit) {
    for (const geometry::Pixel& p : s)
      if (p.x >= shown.x0 && p.x < shown.x1 && p.y >= shown.y0 && p.y < shown.y1)
        who[std::size_t(p.y - shown.y0) * cols + (p.x - shown.x0)] |= bit;
  };
  mark(lit, 1);
  mark(reference, 2);
  mark(violating, 4);
  const Rgb8 colors[8] = {kUnlitColor,     kPlatformOnlyColor, kReferenceOnlyColor, kBothColor,
                          kViolationColor, kViolationColor,    kViolationColor,     kViolationColor};

  // Blocks, rows flipped: window row y (up) is image rows (shown.y1 - 1 - y) * S ... + S - 1.
  pic.rgb.resize(std::size_t(pic.width) * pic.height * 3);
  std::vector<std::pair<int, int>> marked;  // centres of the black blocks, image pixels
  for (int wy = 0; wy < rows; ++wy)
    for (int wx = 0; wx < cols; ++wx) {
      const uint8_t w = who[std::size_t(wy) * cols + wx];
      const Rgb8 fill = colors[w];
      const Rgb8 edge = S >= 8 ? darker(fill) : fill;
      const int top = (rows - 1 - wy) * S, left = wx * S;
      if (w & 4) marked.push_back({left + S / 2, top + S / 2});
      for (int i = 0; i < S; ++i)
        for (int j = 0; j < S; ++j) {
          const Rgb8 c = (i == 0 || j == 0) ? edge : fill;
          uint8_t* px = &pic.rgb[(std::size_t(top + i) * pic.width + left + j) * 3];
          px[0] = c.r, px[1] = c.g, px[2] = c.b;
        }
    }

  // Rings around the marked pixels: clusters of nearby ones share one; too many clusters are
  // joined over longer distances until a reader can take them in.
  if (marked.empty()) return pic;
  std::vector<Cluster> groups;
  for (int join = std::max(kMarkerJoin, S + 1);; join *= 2) {
    groups = clusters(marked, join);
    if (groups.size() <= kMarkerMaxRings || join > pic.width + pic.height) break;
  }
  // beyond the cluster's blocks; in a large picture a larger ring, so that it reads at page size
  const int least = std::max(kMarkerMinRadius, std::max(pic.width, pic.height) / 40);
  const int margin = std::max(least, S / 2 + 6);
  for (const Cluster& g : groups) {
    const auto& b = g.box;
    const int w = b[2] - b[0] + S, h = b[3] - b[1] + S;  // the blocks' extent
    // as much black as a square of kMarkerLargeCluster is seen without a ring; a thin crack is not
    if (g.points * S * S >= int64_t(kMarkerLargeCluster) * kMarkerLargeCluster) {
      ++pic.large_clusters;
      continue;
    }
    MarkerRing r;
    r.cx = (b[0] + b[2]) / 2;
    r.cy = (b[1] + b[3]) / 2;
    r.radius = int(std::ceil(0.5 * std::hypot(double(w), double(h)))) + margin - S / 2;
    r.radius = std::max(r.radius, least);
    r.half_width = std::max(pic.width, pic.height) >= 600 ? 2 : 1;
    pic.rings.push_back(r);
  }
  draw_rings(pic.rgb, pic.width, pic.height, S, pic.rings);
  return pic;
}

PrimitiveImage show_primitive(const ShowRequest& q) {
  const std::string toml = rundir::run_folder::experiment(q.run_dir);
  if (!fs::is_regular_file(toml))
    throw util::UserError(q.run_dir + ": not a run directory (no experiment.toml)");
  const rundir::Experiment exp = rundir::load_run_experiment(q.run_dir);
  const rundir::PlatformSpec platform_spec = rundir::experiment_platform(exp, q.platform);
  geometry::Kind kind;
  if (!geometry::parse_kind(q.kind, &kind))
    throw util::UserError("unknown kind '" + q.kind + "' (allowed: point, line, triangle)");
  check_request(q, exp, kind);

  PrimitiveImage out;
  for (const geometry::View& v : exp.views)
    if (v.id == q.view) out.view = v;
  const geometry::View& view = out.view;
  const geometry::Primitive prim = geometry::make_primitive(exp.seed, kind, q.index);

  // Render once, measure that rendering, and rasterize the reference for comparison.
  const std::unique_ptr<platforms::Platform> platform =
      platforms::create_platform(platform_spec, rundir::fault_plan_for(exp, platform_spec));
  // The driver that made the run's records, or a clear stop (renderer_check.h).
  platforms::require_run_driver(q.run_dir, q.platform, platform->driver_info());
  const bool is_reference = q.platform == "reference";
  // The grid the runner's workers measured (the same calibration: deterministic platforms agree).
  const geometry::SubpixelGrid effective =
      is_reference ? geometry::SubpixelGrid{} : runner::measure_effective_subpixel(*platform).grid;
  RecordingPlatform recorder(*platform);
  recorder.set_view(view);
  runner::CaseComparison comparison(!is_reference, effective);
  comparison.line_rule = runner::line_rule_for(platform_spec, platform->driver_info());
  const bool rectangles = comparison.line_rule == runner::CaseComparison::LineRule::kRectangle;
  out.record = runner::measure_case(q.platform, recorder, view, prim, comparison);
  const geometry::PixelSet& lit = recorder.last.lit;
  geometry::PixelSet reference = geometry::rasterize_reference(view, prim);
  if (rectangles &&
      kind == geometry::Kind::kLine) {  // Vulkan's strict lines: the rectangle's pixels
    const geometry::ClippedSegment segment = geometry::clip_segment(view, prim.v[0], prim.v[1]);
    reference.clear();
    if (segment.status == geometry::ClipStatus::kVisible) {
      const auto [a, b] = rectangle_ends(segment, metrics::near_clipped_vertices(view, prim));
      reference = geometry::rasterize_rectangle_segment(a, b, view.width, view.height);
    }
  }
  geometry::PixelSet violating;
  if (!is_reference) metrics::judge_primitive(view, prim, lit, effective, &violating, rectangles);
  out.violating = violating.size();
  for (const geometry::Pixel& p : lit) (reference.contains(p) ? out.both : out.platform_only) += 1;
  for (const geometry::Pixel& p : reference)
    if (!lit.contains(p)) ++out.reference_only;

  // The window pixels shown.
  const IdealShape ideal = ideal_shape(view, prim);
  geometry::PixelRect shown =
      unite(ideal.rect, unite(around(lit, kImageMargin, view.width, view.height),
                              around(reference, kImageMargin, view.width, view.height)));
  if (shown.empty() || (view.width <= kWholeWindowMax && view.height <= kWholeWindowMax))
    shown = {0, 0, view.width, view.height};
  out.shown = shown;
  const int cols = shown.x1 - shown.x0, rows = shown.y1 - shown.y0;
  const int S = q.scale > 0 ? q.scale : std::max(1, kTargetImageSize / std::max(cols, rows));
  if (int64_t(cols) * S > kMaxImageSide || int64_t(rows) * S > kMaxImageSide)
    throw util::UserError("the image would be " + std::to_string(int64_t(cols) * S) + " x " +
                          std::to_string(int64_t(rows) * S) + " px (at most " +
                          std::to_string(kMaxImageSide) + " per side): choose a smaller --scale");
  out.scale = S;
  out.width = cols * S;
  out.height = rows * S;

  out.picture = draw_pixel_picture(lit, reference, violating, shown, S);
  std::vector<uint8_t> rgb = std::move(out.picture.rgb);
  out.picture.rgb.clear();

  OIIO::ImageSpec spec(out.width, out.height, 3, OIIO::TypeDesc::UINT8);
  spec.attribute("Software", "renderaudit show");
  spec.attribute("ImageDescription", q.platform + " " + geometry::kind_name(kind) + " " +
                                         std::to_string(q.index) + ", view " +
                                         std::to_string(q.view) + " of " + q.run_dir +
                                         ": grey both, orange platform "
                                         "only, blue reference only (both allowed by GL), black "
                                         "a pixel GL forbids lit or missing, ringed in magenta, "
                                         "red the ideal projection");
  OIIO::ImageBuf buf(spec, rgb.data());

  // The ideal projection, 1 px wide, on top. Window (x, y) -> image (column, row), clamped so
  // that ends on the window's far edges land on the last pixel.
  auto to_image = [&](geometry::Vec2 p) {
    const int ix = int(std::floor((p.x - shown.x0) * S));
    const int iy = int(std::floor((shown.y1 - p.y) * S));
    return std::pair<int, int>{std::clamp(ix, 0, out.width - 1), std::clamp(iy, 0, out.height - 1)};
  };
  const float red[3] = {kIdealColor.r / 255.f, kIdealColor.g / 255.f, kIdealColor.b / 255.f};
  auto line = [&](std::pair<int, int> a, std::pair<int, int> b) {
    OIIO::ImageBufAlgo::render_line(buf, a.first, a.second, b.first, b.second, red);
  };
  const std::vector<geometry::Vec2>& pts = ideal.points;
  if (pts.size() == 1) {
    const auto c = to_image(pts[0]);
    const int arm = std::max(3, S / 3);
    line({std::max(0, c.first - arm), c.second},
         {std::min(out.width - 1, c.first + arm), c.second});
    line({c.first, std::max(0, c.second - arm)},
         {c.first, std::min(out.height - 1, c.second + arm)});
  } else if (pts.size() == 2) {
    line(to_image(pts[0]), to_image(pts[1]));
  } else {
    for (std::size_t i = 0; i < pts.size(); ++i)
      line(to_image(pts[i]), to_image(pts[(i + 1) % pts.size()]));
  }

  write_picture(buf, q, kind, out);
  return out;
}

}  // namespace ra::triage
