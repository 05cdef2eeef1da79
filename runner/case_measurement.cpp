#include "runner/case_measurement.h"
#include <stdexcept>

#include "runner/clipping.h"
#include "runner/line_metrics.h"
#include "runner/point_metrics.h"
#include "runner/reference_rasterizer.h"
#include "runner/triangle_metrics.h"

namespace ra {

Record case_identity(const std::string& platform_name, const View& view, const Primitive& prim) {
  Record r;
  r.platform = platform_name;
  r.view = view.id;
  r.view_group = view.group;
  r.orientation = view.orientation;
  r.fov_deg = view.fov_deg;
  r.width = view.width;
  r.height = view.height;
  r.near = view.near;
  r.far = view.far;
  r.kind = kind_name(prim.kind);
  r.index = prim.index;
  return r;
}

namespace {

// Renders a clipped segment or triangle, reading back first around its visible part, and measures
// it with `measure`. False (status invalid, nothing drawn) when the clip found no projection, e.g.
// w = 0 at a vertex.
template <typename Clipped, typename Measure>
bool render_clipped(const Clipped& clipped, Platform& platform, const View& view,
                    const Primitive& prim, Record& rec, RenderResult& rendered, Measure measure) {
  if (clipped.status == ClipStatus::kInvalid) {
    rec.status = CaseStatus::kInvalid;
    return false;
  }
  rendered = platform.render(prim, bounding_rect(clipped, view.width, view.height, kRegionMargin));
  measure(clipped, view, rendered.lit, rec);
  return true;
}

}  // namespace

Record measure_case(const std::string& platform_name, Platform& platform, const View& view,
                    const Primitive& prim, bool compare_with_reference) {
  Record rec = case_identity(platform_name, view, prim);
  for (int i = 0; i < vertex_count(prim.kind); ++i) {
    if (!is_finite(prim.v[i])) {  // never hand a driver NaN or inf, never a silent number
      rec.status = CaseStatus::kInvalid;
      return rec;
    }
  }

  RenderResult rendered;
  switch (prim.kind) {
    case Kind::kPoint: {
      const IdealPoint ideal = project_point(view, prim.v[0]);
      rendered = platform.render(prim, point_region(view, ideal, kRegionMargin));
      measure_point(view, ideal, rendered.lit, rec);
      break;
    }
    case Kind::kLine:
      if (!render_clipped(clip_segment(view, prim.v[0], prim.v[1]), platform, view, prim, rec,
                          rendered, measure_segment_case))
        return rec;
      break;
    case Kind::kTriangle:
      if (!render_clipped(clip_triangle(view, prim.v[0], prim.v[1], prim.v[2]), platform, view,
                          prim, rec, rendered, measure_triangle_case))
        return rec;
      break;
  }
  rec.render_us = rendered.render_us;
  rec.pixel_hash = pixel_set_hash(rendered.lit);
  rec.ref_diff = compare_with_reference
                     ? symmetric_difference_size(rendered.lit, rasterize_reference(view, prim))
                     : 0;
  return rec;
}

void measure_segment_case(const ClippedSegment& seg, const View& view, const PixelSet& lit,
                          Record& rec) {
  rec.pixels = int64_t(lit.size());
  rec.visibility = classify_extended(ideally_visible(seg), lit.size());
  if (rec.visibility != Visibility::kTrueVisible) return;
  const LineMetrics m = measure_line(seg, lit, view.width, view.height);
  rec.lse_s = m.lse_signed;
  rec.lse_u = m.lse_unsigned;
  rec.extent_error = m.extent_error;
  rec.lse_s_norm = m.lse_signed_norm;
  rec.lse_u_norm = m.lse_unsigned_norm;
  rec.chain_8connected = m.chain ? 1 : 0;
  rec.gaps = m.gaps;
}

void measure_triangle_case(const ClippedPolygon& poly, const View& view, const PixelSet& lit,
                           Record& rec) {
  rec.pixels = int64_t(lit.size());
  rec.visibility = classify_extended(ideally_visible(poly), lit.size());
  if (rec.visibility != Visibility::kTrueVisible) return;
  const TriangleMetrics m = measure_triangle(poly, lit, view.width, view.height);
  rec.te_s = m.te_signed;
  rec.te_u = m.te_unsigned;
  rec.te_s_norm = m.te_signed_norm;
  rec.te_u_norm = m.te_unsigned_norm;
  rec.te_u_edge_norm = m.te_unsigned_edge_norm;
  rec.full_window = m.full_window ? 1 : 0;
  rec.simply_connected = m.simply_connected ? 1 : 0;
}

Visibility classify_extended(bool ideal_visible, size_t lit_pixels) {
  if (lit_pixels > 0) return ideal_visible ? Visibility::kTrueVisible : Visibility::kFalseVisible;
  return ideal_visible ? Visibility::kFalseInvisible : Visibility::kTrueInvisible;
}

}  // namespace ra
