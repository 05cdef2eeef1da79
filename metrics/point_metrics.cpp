#include "metrics/point_metrics.h"

#include <cmath>

namespace ra::metrics {

IdealPoint project_point(const geometry::View& view, geometry::Vec3 p) {
  IdealPoint out;
  out.visible = view.point_inside(p);  // depth in eye space: right for every near / far ratio
  if (out.visible) out.window = view.clip_to_window(view.to_clip(p));
  return out;
}

bool inside_window_margin(const geometry::View& view, geometry::Vec3 p, double margin_px) {
  const geometry::Vec4 c = view.to_clip(p);
  const double z_eye = (view.view_matrix * geometry::Vec4{p.x, p.y, p.z, 1.0}).z;
  if (!(c.w > 0 && -view.far < z_eye && z_eye < -view.near)) return false;  // behind, nearer, farther
  const geometry::Vec2 w = view.clip_to_window(c);
  return -margin_px < w.x && w.x < view.width + margin_px && -margin_px < w.y &&
         w.y < view.height + margin_px;
}

geometry::PixelRect point_region(const geometry::View& view, const IdealPoint& ideal, int margin) {
  if (!ideal.visible) return {};
  const int x = int(std::floor(ideal.window.x)), y = int(std::floor(ideal.window.y));
  geometry::PixelRect r{x - margin, y - margin, x + margin + 1, y + margin + 1};
  r.x0 = std::max(r.x0, 0);
  r.y0 = std::max(r.y0, 0);
  r.x1 = std::min(r.x1, view.width);
  r.y1 = std::min(r.y1, view.height);
  return r;
}

Visibility classify_point(bool ideal_visible, size_t lit_pixels) {
  if (lit_pixels > 1) return Visibility::kMultipleVisible;
  if (lit_pixels == 1) return ideal_visible ? Visibility::kTrueVisible : Visibility::kFalseVisible;
  return ideal_visible ? Visibility::kFalseInvisible : Visibility::kTrueInvisible;
}

double point_error(geometry::Vec2 projected, geometry::Pixel rendered) {
  return std::hypot(projected.x - (rendered.x + 0.5), projected.y - (rendered.y + 0.5));
}

void measure_point(const geometry::View& view, const IdealPoint& ideal,
                   const geometry::PixelSet& lit, Record& rec) {
  rec.pixels = int64_t(lit.size());
  rec.visibility = classify_point(ideal.visible, lit.size());
  if (rec.visibility == Visibility::kTrueVisible) {
    rec.pe = point_error(ideal.window, lit.front());
    rec.pe_norm = rec.pe / view.norm_length();
  }
}

}  // namespace ra::metrics
