// What the three studies' experiment files (timing/, terrain_lod/, regulation/) share: the file
// and run name, the camera block and the platform to draw on, read with one wording of errors.
// A study's settings derive from StudySettings and its reader calls these for its own table
// (`where`: "timing", "lod", "regulation").
#pragma once

#include <toml++/toml.h>

#include <set>
#include <string>

#include "scenes/camera.h"
#include "util/toml_locator.h"

namespace ra::scenes {

struct StudySettings {
  std::string file;  // the experiment file, as given
  std::string name;  // `name`, or the file's stem
  CameraSettings camera;
};

// The head of a study's experiment file: parses `text`, rejects top-level keys other than `name`,
// `where` and `other_keys`, sets settings->file and ->name, and returns root and the [where]
// table. Without [where]: UserError "the file needs a [where] table" when `required`, else an
// empty table; "'where' must be a table" when it is something else.
struct StudyFile {
  toml::table root;
  const toml::table& table() const { return table_ ? *table_ : empty_; }  // [where], or empty

  const toml::table* table_ = nullptr;  // a node of root (nodes stay put when root moves)
  toml::table empty_;
};
StudyFile read_study_file(const util::TomlLocator& loc, const std::string& text,
                          const std::string& where, const std::set<std::string>& other_keys,
                          bool required, StudySettings* settings);

// The keys of the camera block: window = [width, height] (pixels, 16..4096 each), fov_deg
// (vertical, degrees, 0 < fov_deg < 180), near (> 0) and far (> near), clip planes in metres.
extern const char* const kCameraKeys[4];

// Reads the camera keys present in `table` (the table `where`) into `camera`, keeping its values
// for the absent ones; UserError "file:line:column: 'where.key' ..." naming the allowed range.
void read_camera_block(const util::TomlLocator& loc, const toml::table& table,
                       const std::string& where, CameraSettings* camera);

// A platform the studies can time: a GL platform that draws aliased frames (a multisample
// platform would be measured as aliased; the reference has no GL to time). UserError "'key' =
// "NAME" is out of range (allowed: ...)" otherwise.
std::string read_study_platform(const util::TomlLocator& loc, const toml::node& node,
                                const std::string& key);

}  // namespace ra::scenes
