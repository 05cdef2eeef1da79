#include "runner/case_measurement.h"
#include <stdexcept>

#include "runner/point_metrics.h"
#include "runner/reference_platform.h"

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
      rendered = platform.render(prim, point_region(view, ideal));
      measure_point(view, ideal, rendered.lit, rec);
      break;
    }
    case Kind::kLine:
    case Kind::kTriangle:
      throw std::logic_error("lines and triangles are not measured yet");
  }
  rec.render_us = rendered.render_us;
  rec.pixel_hash = pixel_set_hash(rendered.lit);
  rec.ref_diff = compare_with_reference
                     ? symmetric_difference_size(rendered.lit, reference_render(view, prim))
                     : 0;
  return rec;
}

}  // namespace ra
