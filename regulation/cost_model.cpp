// Time and perceptual cost of an object's levels (cost_model.h).
#include "regulation/cost_model.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "util/atomic_file.h"
#include "util/errors.h"
#include "util/json_file.h"

namespace ra::regulation {

double predict_us(const CostModel& m, double tv, double pixels) {
  return m.intercept_us + m.c1_us_per_tv * tv + m.c2_us_per_pixel * pixels * m.pixel_factor;
}

int64_t cost_units(const CostModel& m, double us) {
  return std::max<int64_t>(0, int64_t(std::ceil(us / m.cost_unit_us - 1e-9)));
}

CostModel cost_model_from_timing_json(const std::string& path, const std::string& platform,
                                      bool intercept, const CostModel& base) {
  nlohmann::json j;
  try {
    j = util::parse_json_document(util::read_file(path), path);
  } catch (const std::exception& e) {
    throw util::UserError(path + ": cannot read the timing study's output (" + e.what() + ")");
  }
  for (const auto& p : j.value("platforms", nlohmann::json::array())) {
    if (p.value("name", "") != platform) continue;
    for (const auto& f : p.value("fits", nlohmann::json::array())) {
      if (f.value("heuristic", "") != "h4" || f.value("intercept", false) != intercept) continue;
      CostModel m = base;
      m.intercept_us = 0;
      const std::string fit = std::string("h4") + (intercept ? "+b" : "");
      auto bad = [&](const std::string& what) {
        return util::UserError(path + ": the " + fit + " fit of platform " + platform + " " + what);
      };
      bool have_c1 = false, have_c2 = false, have_b0 = false;
      const auto params = f.value("parameters", nlohmann::json::array());
      if (!params.is_array()) throw bad("has no parameter list");
      for (const auto& c : params) {
        const std::string name = c.is_object() ? c.value("name", "") : "";
        if (!c.is_object() || !c.contains("value") || !c["value"].is_number())
          throw bad("has parameter '" + name + "' that is not a number");
        const double v = c["value"].get<double>();
        if (!std::isfinite(v)) throw bad("has parameter '" + name + "' that is not finite");
        if (name == "c1") m.c1_us_per_tv = v, have_c1 = true;
        else if (name == "c2") m.c2_us_per_pixel = v, have_c2 = true;
        else if (name == "b0") m.intercept_us = v, have_b0 = true;
      }
      if (!have_c1) throw bad("lacks parameter 'c1' (us per transformed vertex)");
      if (!have_c2) throw bad("lacks parameter 'c2' (us per pixel)");
      if (intercept && !have_b0) throw bad("lacks parameter 'b0' (the intercept)");
      if (m.c1_us_per_tv < 0)
        throw bad("has parameter 'c1' = " + std::to_string(m.c1_us_per_tv) + " (allowed: >= 0)");
      if (m.c2_us_per_pixel < 0)
        throw bad("has parameter 'c2' = " + std::to_string(m.c2_us_per_pixel) + " (allowed: >= 0)");
      m.source = path + " (" + platform + ", h4" + (intercept ? "+b" : "") + ")";
      return m;
    }
  }
  throw util::UserError(path + ": no h4" + std::string(intercept ? "+b" : "") +
                        " fit for platform " + platform);
}

Footprint footprint_of(const scenes::BoundingSphere& s, const geometry::Mat4& view,
                       const scenes::Frustum& frustum, const scenes::CameraSettings& cam) {
  Footprint f;
  const double W = cam.width, H = cam.height;
  f.focal_px = 0.5 * H / std::tan(cam.half_fov_y());
  const geometry::Vec4 c = view * geometry::Vec4{s.centre.x, s.centre.y, s.centre.z, 1.0};
  f.distance_m = std::sqrt(c.x * c.x + c.y * c.y + c.z * c.z);
  f.visible = frustum.intersects(s);
  if (!f.visible) return f;
  const double depth = -c.z;  // the camera looks down -z
  if (f.distance_m <= s.radius * 1.0001 || depth <= 0) {
    f.pixels = W * H;  // the eye is inside (or level with) the sphere: take the whole window
  } else {
    const double r_px = f.focal_px * s.radius / std::sqrt(f.distance_m * f.distance_m - s.radius * s.radius);
    const double sx = 0.5 * W + f.focal_px * c.x / depth, sy = 0.5 * H + f.focal_px * c.y / depth;
    const double wx = std::max(0.0, std::min(sx + r_px, W) - std::max(sx - r_px, 0.0));
    const double wy = std::max(0.0, std::min(sy + r_px, H) - std::max(sy - r_px, 0.0));
    f.pixels = std::min(W * H, M_PI / 4 * wx * wy);
  }
  f.area_fraction = f.pixels / (W * H);
  return f;
}

double perceptual_cost(double area_fraction, double error_m, double distance_m, double focal_px,
                       double exponent) {
  if (!(error_m > 0)) return 0;
  const double e_px = error_m * focal_px / std::max(distance_m, 1e-6);
  return area_fraction * std::pow(e_px, exponent);
}

}  // namespace ra::regulation
