// The shared head of the study experiment files (study_settings.h).
#include "scenes/study_settings.h"

#include <sstream>

#include "geometry/projection_range.h"
#include "rundir/platform_spec.h"
#include "util/number_text.h"

namespace ra::scenes {
StudyFile read_study_file(const util::TomlLocator& loc, const std::string& text,
                          const std::string& where, const std::set<std::string>& other_keys,
                          bool required, StudySettings* s) {
  StudyFile f{loc.parse(text), nullptr, {}};
  std::set<std::string> keys = other_keys;
  keys.insert({"name", where});
  loc.reject_unknown_keys(f.root, "", keys);
  s->file = loc.path();
  s->name = loc.experiment_name(f.root);
  const toml::node* n = f.root.get(where);
  if (!n && required) loc.fail(nullptr, "the file needs a [" + where + "] table");
  if (n && !n->is_table()) loc.fail(n, "'" + where + "' must be a table");
  f.table_ = n ? n->as_table() : nullptr;  // copying a table would lose its source positions
  return f;
}

const char* const kCameraKeys[4] = {"window", "fov_deg", "near", "far"};

void read_camera_block(const util::TomlLocator& loc, const toml::table& t, const std::string& where,
                       CameraSettings* cam) {
  const std::string p = where + ".";
  if (const auto* n = t.get("window")) {
    const auto& a = loc.array(*n, p + "window", 2, 2, "[width, height] in pixels");
    cam->width = int(loc.integer(*a.get(0), p + "window", 16, 4096));
    cam->height = int(loc.integer(*a.get(1), p + "window", 16, 4096));
  }
  if (const auto* n = t.get("fov_deg"))
    cam->fov_y_deg = loc.number(*n, p + "fov_deg", "0 < fov_deg < 180, vertical",
                                [](double v) { return v > 0 && v < 180; });
  if (const auto* n = t.get("near"))
    cam->near = loc.number(*n, p + "near", "near > 0 metres", [](double v) { return v > 0; });
  const double near = cam->near;
  if (const auto* n = t.get("far"))
    cam->far = loc.number(*n, p + "far", "far > near = " + util::significant(near, 6),
                          [near](double v) { return v > near; });
  else if (!(cam->far > near))
    loc.fail(t.get("near"), "'" + p + "near' = " + util::significant(near, 6) +
                                " is out of range (allowed: near < far = " + util::significant(cam->far, 6) + ")");
  // The projection must be finite in double and in float (drivers transform in float): what is
  // drawn lies within `far` of the camera in eye space, so with the entries f/aspect, f,
  // A = (far+near)/(near-far) and B = 2*far*near/(near-far) of the projection, clip x, y and z are
  // at most f/aspect*far, f*far and |A|*far + |B|; each must be at most FLT_MAX
  // (geometry::depth_projection_problem, lateral_projection_problem).
  if (const std::string why = geometry::depth_projection_problem(near, cam->far, cam->far);
      !why.empty())
    loc.fail(t.get("far") ? t.get("far") : t.get("near"),
             "'" + p + "far' = " + util::significant(cam->far, 6) + " with near = " +
                 util::significant(near, 6) + " is out of range: " + why +
                 " (allowed: near < far with the clip coordinates of what lies within far of the "
                 "camera at most 3.40282e+38, the float range)");
  if (const std::string why = geometry::lateral_projection_problem(
          cam->fov_y_deg, double(cam->width) / cam->height, cam->far);
      !why.empty())
    loc.fail(t.get("fov_deg") ? t.get("fov_deg") : t.get("far"),
             "'" + p + "fov_deg' = " + util::significant(cam->fov_y_deg, 6) + " with far = " +
                 util::significant(cam->far, 6) + " is out of range: " + why +
                 " (allowed: 0 < fov_deg < 180 with 1/tan(fov_deg/2) * max(1, height/width) * "
                 "far at most 3.40282e+38, the float range)");
}

std::string read_study_platform(const util::TomlLocator& loc, const toml::node& node,
                                const std::string& key) {
  const std::string name = loc.string(node, key, {}, rundir::aliased_gl_platform_names());
  if (!rundir::is_aliased_gl_platform(name))
    loc.fail(&node, "'" + key + "' = \"" + name + "\" is out of range (allowed: " +
                        rundir::aliased_gl_platform_names() + ")");
  return name;
}

}  // namespace ra::scenes
