// Tests of the shared head of the study experiment files (study_settings.h): one wording of the
// camera block's errors, whichever study reads it, located at file:line:column.
#include "scenes/study_settings.h"

#include <gtest/gtest.h>

#include "util/errors.h"

namespace ra::scenes {
namespace {

// The error of reading `text` as study `where`'s file, "" when it reads.
std::string error_of(const std::string& text, const std::string& where = "lod") {
  try {
    const util::TomlLocator loc("s.toml");
    StudySettings s;
    const StudyFile f = read_study_file(loc, text, where, {}, true, &s);
    read_camera_block(loc, f.table(), where, &s.camera);
    if (const auto* n = f.table().get("platform")) read_study_platform(loc, *n, where + ".platform");
    return "";
  } catch (const util::UserError& e) {
    return e.what();
  }
}

TEST(StudySettings, ReadsTheCameraBlock) {
  const util::TomlLocator loc("s.toml");
  StudySettings s;
  const StudyFile f = read_study_file(
      loc, "name = \"n1\"\n[timing]\nwindow = [320, 200]\nfov_deg = 45\nnear = 2\nfar = 900\n", "timing", {},
      true, &s);
  read_camera_block(loc, f.table(), "timing", &s.camera);
  EXPECT_EQ(s.file, "s.toml");
  EXPECT_EQ(s.name, "n1");
  EXPECT_EQ(s.camera.width, 320);
  EXPECT_EQ(s.camera.height, 200);
  EXPECT_EQ(s.camera.fov_y_deg, 45);
  EXPECT_EQ(s.camera.near, 2);
  EXPECT_EQ(s.camera.far, 900);
}

TEST(StudySettings, OneWordingOfErrors) {
  EXPECT_EQ(error_of("[regulation]\nwindow = [640]\n", "regulation"),
            "s.toml:2:10: 'regulation.window' must be [width, height] in pixels");
  EXPECT_EQ(error_of("[lod]\nwindow = [640, 8]\n"),
            "s.toml:2:16: 'lod.window' = 8 is out of range (allowed: 16 to 4096)");
  EXPECT_EQ(error_of("[timing]\nfov_deg = 180\n", "timing"),
            "s.toml:2:11: 'timing.fov_deg' = 180 is out of range (allowed: 0 < fov_deg < 180, vertical)");
  EXPECT_EQ(error_of("[lod]\nnear = 10\nfar = 5\n"),
            "s.toml:3:7: 'lod.far' = 5 is out of range (allowed: far > near = 10)");
  // far left at its default (20000 m) below a given near
  EXPECT_EQ(error_of("[lod]\nnear = 30000\n"),
            "s.toml:2:8: 'lod.near' = 30000 is out of range (allowed: near < far = 20000)");
  EXPECT_EQ(error_of("[lod]\nplatform = \"reference\"\n").rfind("s.toml:2:12: 'lod.platform' = \"reference\" is out "
                                                              "of range (allowed: ", 0),
            0u);
  EXPECT_EQ(error_of("name = \"x\"\n"), "s.toml:1:1: the file needs a [lod] table");
}

// A camera whose projection overflows in double or float is refused at its key, with the range.
TEST(StudySettings, AProjectionBeyondTheFloatRangeIsRefused) {
  for (const char* far : {"1e308", "9e307", "1e39"}) {
    const std::string e = error_of(std::string("[lod]\nnear = 1\nfar = ") + far + "\n");
    EXPECT_EQ(e.rfind("s.toml:3:7: 'lod.far' = ", 0), 0u) << e;
    EXPECT_NE(e.find("is out of range: "), std::string::npos) << e;
    EXPECT_NE(e.find("3.40282e+38, the float range)"), std::string::npos) << e;
  }
  const std::string e = error_of("[lod]\nfov_deg = 1e-36\n");
  EXPECT_EQ(e.rfind("s.toml:2:11: 'lod.fov_deg' = 1e-36 with far = 20000 is out of range: ", 0), 0u)
      << e;
  EXPECT_EQ(error_of("[lod]\nnear = 1\nfar = 1e30\n"), "");
  EXPECT_EQ(error_of("lod = 3\n"), "s.toml:1:7: 'lod' must be a table");
  EXPECT_EQ(error_of("[lod]\n[extra]\n"), "s.toml:2:2: unknown key 'extra' (allowed: lod, name)");
}

}  // namespace
}  // namespace ra::scenes
