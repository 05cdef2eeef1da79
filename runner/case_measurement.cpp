#include "runner/case_measurement.h"
#include <chrono>
#include <stdexcept>
#include <vector>

#include "geometry/clipping.h"
#include "metrics/conformance.h"
#include "metrics/line_metrics.h"
#include "metrics/point_metrics.h"
#include "geometry/reference_rasterizer.h"
#include "metrics/triangle_metrics.h"
#include "platforms/layer_packing.h"

namespace ra::runner {

metrics::Record case_identity(const std::string& platform_name, const geometry::View& view,
                     const geometry::Primitive& prim) {
  metrics::Record r;
  r.platform = platform_name;
  r.view = view.id;
  r.view_group = view.group;
  r.orientation = view.orientation;
  r.fov_deg = view.fov_deg;
  r.width = view.width;
  r.height = view.height;
  r.near = view.near;
  r.far = view.far;
  r.kind = geometry::kind_name(prim.kind);
  r.index = prim.index;
  return r;
}

namespace {

// The ideal side of one case, computed before anything is drawn.
struct PreparedCase {
  metrics::Record rec;              // identity; status kInvalid when nothing may be drawn
  metrics::IdealPoint point;        // Kind::kPoint
  geometry::ClippedSegment segment;  // Kind::kLine
  geometry::ClippedPolygon polygon;  // Kind::kTriangle
  geometry::PixelRegion expected;    // where the ideal primitive lies, plus kRegionMargin
};

// A small triangle's box is read back whole (one call, and it can share a batch); a large one's in
// bands of 32 rows that follow its sides: it fills at most half its box, and the readback copy and
// scan were a fifth of a 907 x 907 llvmpipe triangle's time (docs/benchmarks.md).
geometry::PixelRegion triangle_region(const geometry::ClippedPolygon& polygon, int width,
                                      int height) {
  const geometry::PixelRect box = geometry::bounding_rect(polygon, width, height, kRegionMargin);
  if (box.area() <= kTriangleBandMinArea) return box;
  return geometry::band_region(polygon, width, height, kRegionMargin, kTriangleBandRows);
}

PreparedCase prepare_case(const std::string& platform_name, const geometry::View& view,
                          const geometry::Primitive& prim) {
  PreparedCase c;
  c.rec = case_identity(platform_name, view, prim);
  for (int i = 0; i < geometry::vertex_count(prim.kind); ++i) {
    if (!geometry::is_finite(prim.v[i])) {  // never hand a driver NaN or inf, never a silent number
      c.rec.status = metrics::CaseStatus::kInvalid;
      return c;
    }
  }
  switch (prim.kind) {
    case geometry::Kind::kPoint:
      c.point = metrics::project_point(view, prim.v[0]);
      c.expected = metrics::point_region(view, c.point, kRegionMargin);
      break;
    case geometry::Kind::kLine:
      c.segment = geometry::clip_segment(view, prim.v[0], prim.v[1]);
      // No projection (e.g. w = 0 at a vertex): status invalid, nothing drawn.
      if (c.segment.status == geometry::ClipStatus::kInvalid) c.rec.status = metrics::CaseStatus::kInvalid;
      c.expected = geometry::strip_region(c.segment, view.width, view.height, kRegionMargin);
      break;
    case geometry::Kind::kTriangle:
      c.polygon = geometry::clip_triangle(view, prim.v[0], prim.v[1], prim.v[2]);
      if (c.polygon.status == geometry::ClipStatus::kInvalid) c.rec.status = metrics::CaseStatus::kInvalid;
      c.expected = triangle_region(c.polygon, view.width, view.height);
      break;
  }
  return c;
}

// Vulkan's strict line (conformance.h judge_rectangle_segment): the rectangle between the ends the
// near and far planes leave; nothing when the segment is not visible.
geometry::PixelSet rectangle_reference(const geometry::ClippedSegment& segment,
                                       const geometry::View& view,
                                       const geometry::Primitive& prim) {
  if (segment.status != geometry::ClipStatus::kVisible) return {};
  const auto [a, b] = metrics::rectangle_ends(segment, metrics::near_clipped_vertices(view, prim));
  return geometry::rasterize_rectangle_segment(a, b, view.width, view.height);
}

metrics::Record finish_case(PreparedCase& c, const geometry::View& view, const geometry::Primitive& prim,
                   const platforms::RenderResult& rendered, const CaseComparison& comparison) {
  metrics::Record& rec = c.rec;
  switch (prim.kind) {
    case geometry::Kind::kPoint:
      metrics::measure_point(view, c.point, rendered.lit, rec);
      break;
    case geometry::Kind::kLine:
      measure_segment_case(c.segment, view, rendered.lit, rec);
      break;
    case geometry::Kind::kTriangle:
      // Points and lines of an antialiased rendering are measured on the pixels with any
      // coverage, as lit pixels; triangles compare coverage with area.
      if (rendered.samples > 0)
        measure_triangle_coverage_case(c.polygon, view, rendered, rec);
      else
        measure_triangle_case(c.polygon, view, rendered.lit, rec);
      break;
  }
  rec.render_us = rendered.render_us;
  rec.host_us = rendered.host_us;
  rec.clock = rendered.device_clock ? "device" : "host";
  rec.batch_size = rendered.batch_size;
  rec.pixel_hash = rendered_pixel_hash(rendered);
  if (!comparison.with_reference) {
    rec.ref_diff = 0;
    rec.conformance = metrics::Conformance::kExact;
    rec.violating_pixels = 0;
    return rec;
  }
  // The reference rasterizer, from the geometry prepare_case already clipped.
  const int w = view.width, h = view.height;
  const bool rectangle_lines = comparison.line_rule == CaseComparison::LineRule::kRectangle;
  geometry::PixelSet reference;
  switch (prim.kind) {
    case geometry::Kind::kPoint:
      reference = geometry::rasterize_reference(view, prim);
      break;
    case geometry::Kind::kLine:
      reference = rectangle_lines ? rectangle_reference(c.segment, view, prim)
                                  : geometry::rasterize_segment(c.segment, w, h);
      break;
    case geometry::Kind::kTriangle:
      reference = geometry::rasterize_polygon(c.polygon, w, h);
      break;
  }
  rec.ref_diff = geometry::symmetric_difference_size(rendered.lit, reference);
  // Coverage (multisample) renderings are not judged: GL's multisample rules are another test.
  if (!comparison.conformance || rendered.samples > 0) return rec;
  if (rec.ref_diff == 0) {  // the usual case, settled without the judge
    rec.conformance = metrics::Conformance::kExact;
    rec.violating_pixels = 0;
    return rec;
  }
  metrics::ConformanceVerdict v;
  switch (prim.kind) {
    case geometry::Kind::kPoint:
      v = metrics::judge_point(metrics::clip_with_error(view, prim.v[0]), w, h, rendered.lit, reference,
                      comparison.effective);
      break;
    case geometry::Kind::kLine:
      v = rectangle_lines
              ? metrics::judge_rectangle_segment(c.segment, metrics::near_clipped_vertices(view, prim), w, h,
                                        rendered.lit, reference, comparison.effective)
              : metrics::judge_segment(c.segment, metrics::near_clipped_vertices(view, prim), w, h, rendered.lit,
                              reference, comparison.effective);
      break;
    case geometry::Kind::kTriangle:
      v = metrics::judge_polygon(c.polygon, metrics::near_clipped_vertices(view, prim), w, h, rendered.lit,
                        reference, comparison.effective);
      break;
  }
  rec.conformance = v.conformance;
  rec.violating_pixels = v.violating_pixels;
  rec.violated_rules = std::move(v.violated_rules);
  return rec;
}

}  // namespace

CaseComparison::LineRule line_rule_for(const rundir::PlatformSpec& spec,
                                       const platforms::DriverInfo& driver) {
  return spec.draws_with_vulkan() &&
                 spec.line_mode == rundir::PlatformSpec::LineMode::kDefault &&
                 driver.strict_lines
             ? CaseComparison::LineRule::kRectangle
             : CaseComparison::LineRule::kDiamondExit;
}

std::vector<metrics::Record> measure_cases(const std::string& platform_name, platforms::Platform& platform,
                                  const geometry::View& view,
                                  const std::vector<geometry::Primitive>& prims,
                                  const CaseComparison& comparison, std::vector<double>* cost_us,
                                  size_t max_batch) {
  using Clock = std::chrono::steady_clock;
  auto since = [](Clock::time_point t0) {
    return std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
  };
  std::vector<double> cost(prims.size(), 0.0);
  std::vector<PreparedCase> cases;
  cases.reserve(prims.size());
  for (size_t i = 0; i < prims.size(); ++i) {
    const auto t0 = Clock::now();
    cases.push_back(prepare_case(platform_name, view, prims[i]));
    cost[i] += since(t0);
  }

  std::vector<metrics::Record> records(prims.size());
  std::vector<size_t> batch;  // indices into prims
  std::vector<geometry::Primitive> batch_prims;
  std::vector<geometry::PixelRegion> batch_regions;
  std::vector<int> batch_layers;
  platforms::LayerPacker packer(max_batch > 1 ? platform.batch_layers() : 1,
                                std::max<size_t>(1, std::min(max_batch, kMaxBatch)),
                                kBatchMaxRegionArea);
  auto flush = [&] {
    if (batch.empty()) return;
    auto t0 = Clock::now();
    const std::vector<platforms::RenderResult> results =
        platform.render_batch(batch_prims, batch_regions, batch_layers);
    const double shared = since(t0) / double(batch.size());  // the batch shares its proof
    for (size_t k = 0; k < batch.size(); ++k) {
      t0 = Clock::now();
      records[batch[k]] = finish_case(cases[batch[k]], view, prims[batch[k]], results[k],
                                      comparison);
      cost[batch[k]] += shared + since(t0);
    }
    batch.clear(), batch_prims.clear(), batch_regions.clear(), batch_layers.clear();
    packer.clear();
  };
  for (size_t i = 0; i < prims.size(); ++i) {
    if (cases[i].rec.status == metrics::CaseStatus::kInvalid) {
      records[i] = cases[i].rec;
      continue;
    }
    // Small primitives with disjoint regions share a layer; one that overlaps them takes another
    // layer, a large one a layer of its own (platforms/layer_packing.h). On a platform with one
    // layer, a batch is small primitives with disjoint regions under one completeness proof, and
    // a large primitive goes alone.
    const geometry::PixelRegion& r = cases[i].expected;
    int layer = packer.place(r);
    if (layer < 0) {
      flush();
      layer = packer.place(r);
    }
    batch.push_back(i), batch_prims.push_back(prims[i]), batch_regions.push_back(r);
    batch_layers.push_back(layer);
  }
  flush();
  if (cost_us) *cost_us = std::move(cost);
  return records;
}

metrics::Record measure_case(const std::string& platform_name, platforms::Platform& platform,
                    const geometry::View& view, const geometry::Primitive& prim,
                    const CaseComparison& comparison) {
  return measure_cases(platform_name, platform, view, {prim}, comparison).front();
}

void measure_segment_case(const geometry::ClippedSegment& seg, const geometry::View& view,
                          const geometry::PixelSet& lit, metrics::Record& rec) {
  rec.pixels = int64_t(lit.size());
  rec.visibility = classify_extended(geometry::ideally_visible(seg), lit.size());
  if (rec.visibility != metrics::Visibility::kTrueVisible) return;
  const metrics::LineMetrics m = metrics::measure_line(seg, lit, view.width, view.height);
  rec.lse_s = m.lse_signed;
  rec.lse_u = m.lse_unsigned;
  rec.extent_error = m.extent_error;
  rec.lse_s_norm = m.lse_signed_norm;
  rec.lse_u_norm = m.lse_unsigned_norm;
  rec.chain_8connected = m.chain ? 1 : 0;
  rec.gaps = m.gaps;
}

namespace {

// The triangle columns of a record from its metrics (aliased or coverage form alike).
void set_triangle_columns(const metrics::TriangleMetrics& m, metrics::Record& rec) {
  rec.te_s = m.te_signed;
  rec.te_u = m.te_unsigned;
  rec.te_s_norm = m.te_signed_norm;
  rec.te_u_norm = m.te_unsigned_norm;
  rec.te_u_edge_norm = m.te_unsigned_edge_norm;
  rec.full_window = m.full_window ? 1 : 0;
  rec.simply_connected = m.simply_connected ? 1 : 0;
}

}  // namespace

void measure_triangle_case(const geometry::ClippedPolygon& poly, const geometry::View& view,
                           const geometry::PixelSet& lit, metrics::Record& rec) {
  rec.pixels = int64_t(lit.size());
  rec.visibility = classify_extended(geometry::ideally_visible(poly), lit.size());
  if (rec.visibility != metrics::Visibility::kTrueVisible) return;
  set_triangle_columns(metrics::measure_triangle(poly, lit, view.width, view.height), rec);
}

void measure_triangle_coverage_case(const geometry::ClippedPolygon& poly,
                                    const geometry::View& view,
                                    const platforms::RenderResult& rendered, metrics::Record& rec) {
  rec.pixels = int64_t(rendered.lit.size());
  rec.visibility = classify_extended(geometry::ideally_visible(poly), rendered.lit.size());
  if (rec.visibility != metrics::Visibility::kTrueVisible) return;
  set_triangle_columns(metrics::measure_triangle_coverage(poly, rendered.lit, rendered.samples_lit,
                                                 rendered.samples, view.width, view.height),
                       rec);
}

uint64_t rendered_pixel_hash(const platforms::RenderResult& rendered) {
  uint64_t h = geometry::pixel_set_hash(rendered.lit);
  if (rendered.samples <= 0) return h;
  for (uint8_t k : rendered.samples_lit) {  // FNV-1a, continued
    h ^= k;
    h *= 0x100000001b3ull;
  }
  return h;
}

metrics::Visibility classify_extended(bool ideal_visible, size_t lit_pixels) {
  if (lit_pixels > 0) return ideal_visible ? metrics::Visibility::kTrueVisible : metrics::Visibility::kFalseVisible;
  return ideal_visible ? metrics::Visibility::kFalseInvisible : metrics::Visibility::kTrueInvisible;
}

}  // namespace ra::runner
