// The shared head of the study experiment files (study_settings.h).
#include "scenes/study_settings.h"

#include <sstream>

#include "platforms/platform.h"
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
