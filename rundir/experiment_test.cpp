// Experiment files: every validation error stops with file:line:column and the allowed values.
#include "rundir/experiment.h"

#include <gtest/gtest.h>

#include "util/errors.h"

namespace ra::rundir {
namespace {

const char* kValid = R"(seed = 1
platforms = ["osmesa-llvmpipe"]
[views]
orientations = 2
fov_deg = [30, 150]
windows = [128, 907]
near = 0.01
far = 10.0
[primitives]
points = 10
)";

// Replaces the first occurrence of `from` in the valid file by `to`.
std::string with(const std::string& from, const std::string& to) {
  std::string s = kValid;
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

// Parses `text` and returns the error message ("" when it parsed).
std::string error_of(const std::string& text) {
  try {
    parse_experiment(text, "exp.toml");
  } catch (const util::UserError& e) {
    return e.what();
  }
  return "";
}

TEST(Experiment, ValidFileGivesTheTable1Views) {
  const Experiment e = parse_experiment(kValid, "dir/exp.toml");
  EXPECT_EQ(e.name, "exp");
  ASSERT_EQ(e.views.size(), 8u);
  // Paper's Table 1 order: orientation innermost, then FOV, then window.
  EXPECT_EQ(e.views[0].orientation, 1);
  EXPECT_EQ(e.views[1].orientation, 2);
  EXPECT_EQ(e.views[2].fov_deg, 150);
  EXPECT_EQ(e.views[4].width, 907);
  EXPECT_EQ(e.views[7].group, 3);
  EXPECT_EQ(e.views[7].group_name(), "D");
  EXPECT_EQ(e.counts[int(geometry::Kind::kPoint)], 10u);
}

TEST(Experiment, HashIgnoresCommentsAndRunSettings) {
  const std::string a = parse_experiment(kValid, "a.toml").hash;
  EXPECT_EQ(a, parse_experiment(std::string("# a comment\n") + kValid + "[run]\nshard_size = 3\n",
                                "b.toml").hash);
  EXPECT_NE(a, parse_experiment(with("seed = 1", "seed = 2"), "c.toml").hash);
}

struct BadCase {
  const char* name;
  std::string text;
  const char* location;  // "exp.toml:LINE:COL"
  const char* says;      // part of the message
};

void PrintTo(const BadCase& c, std::ostream* os) { *os << c.name; }

class ExperimentErrors : public testing::TestWithParam<BadCase> {};

TEST_P(ExperimentErrors, StopWithALocatedMessage) {
  const BadCase& c = GetParam();
  const std::string msg = error_of(c.text);
  EXPECT_NE(msg.find(c.location), std::string::npos) << msg;
  EXPECT_NE(msg.find(c.says), std::string::npos) << msg;
}

INSTANTIATE_TEST_SUITE_P(
    AllRules, ExperimentErrors,
    testing::Values(
        BadCase{"UnknownKey", with("[primitives]", "[primitives]\npoint = 3"), "exp.toml:10:1",
                "unknown key 'primitives.point'; did you mean 'points'? (allowed: lines, points, triangles)"},
        BadCase{"UnknownTopLevelKey", with("seed = 1", "seed = 1\nsede = 2"), "exp.toml:2:1",
                "unknown key 'sede'"},
        BadCase{"WrongType", with("points = 10", "points = \"ten\""), "exp.toml:10:10",
                "'primitives.points' must be an integer (allowed: 0 to 100000000)"},
        BadCase{"NegativeCount", with("points = 10", "points = -5"), "exp.toml:10:10",
                "out of range (allowed: 0 to 100000000)"},
        BadCase{"AbsurdCount", with("points = 10", "points = 1000000000000"), "exp.toml:10:10",
                "out of range"},
        BadCase{"NothingToDo", with("points = 10", "points = 0"), "exp.toml:9:1", "asks for nothing"},
        BadCase{"WindowZero", with("[128, 907]", "[0, 907]"), "exp.toml:6:12",
                "out of range (allowed: 1 to 16384)"},
        BadCase{"WindowTooLarge", with("[128, 907]", "[128, 16385]"), "exp.toml:6:17",
                "out of range (allowed: 1 to 16384)"},
        BadCase{"FovZero", with("[30, 150]", "[0, 150]"), "exp.toml:5:12",
                "allowed: 0 < fov_deg < 180"},
        BadCase{"Fov180", with("[30, 150]", "[30, 180]"), "exp.toml:5:16",
                "allowed: 0 < fov_deg < 180"},
        BadCase{"NearZero", with("near = 0.01", "near = 0"), "exp.toml:7:8",
                "allowed: 0 < near < far"},
        BadCase{"NearBeyondFar", with("near = 0.01", "near = 20"), "exp.toml:8:7",
                "allowed: 0 < near < far"},
        BadCase{"NearEqualsFar", with("near = 0.01", "near = 10.0"), "exp.toml:8:7",
                "beyond the near plane"},
        BadCase{"FarOverflowsDouble", with("far = 10.0", "far = 1e308"), "exp.toml:8:7",
                "'views.far' = 1e+308 with views.near = 0.01 is out of range: "
                "2*far*near/(near-far) is -inf, not a finite double (allowed: 0 < near < far with "
                "2*far and 2*far*near at most 1.79769e+308"},
        BadCase{"FarJustPastHalfTheDoubleRange", with("far = 10.0", "far = 9e307"), "exp.toml:8:7",
                "2*far*near/(near-far) is -inf, not a finite double"},
        BadCase{"DepthBeyondFloat", with("near = 0.01\nfar = 10.0", "near = 2e38\nfar = 3e38"),
                "exp.toml:8:7", "2*far*near/(near-far) is -1.2e+39, beyond the float range"},
        BadCase{"PlanesTooCloseForFloat",
                with("near = 0.01\nfar = 10.0", "near = 1e30\nfar = 1.0000000000000002e30"),
                "exp.toml:8:7", "beyond the float range"},
        BadCase{"FovTooNarrowForFloat", with("[30, 150]", "[30, 1e-37]"), "exp.toml:5:16",
                "'views.fov_deg' = 1e-37 with window 128 x 128 is out of range: "
                "1/tan(fov/2)/aspect is 1.14592e+39, beyond the float range"},
        BadCase{"UnknownPlatform", with("\"osmesa-llvmpipe\"", "\"swrast\""), "exp.toml:2:14",
                "unknown platform 'swrast' (allowed: osmesa-llvmpipe, osmesa-softpipe, reference"},
        BadCase{"MissingSeed", with("seed = 1", ""), "exp.toml:1:1", "missing key 'seed'"},
        BadCase{"SyntaxError", with("seed = 1", "seed = = 1"), "exp.toml:1:8",
                "could not determine value type"},
        BadCase{"ZeroOrientations", with("orientations = 2", "orientations = 0"), "exp.toml:4:16",
                "out of range (allowed: 1 to 1000)"},
        BadCase{"BadOrientation", with("orientations = 2", "orientations = [[1, 2]]"),
                "exp.toml:4:17", "[yaw, pitch, roll]"},
        BadCase{"FaultsWithoutFaulty", with("[primitives]", "[faults]\ncrash = [1]\n[primitives]"),
                "exp.toml:9:1", "only applies to the 'faulty' test platform"},
        BadCase{"ShardSizeZero", std::string(kValid) + "[run]\nshard_size = 0\n", "exp.toml:12:14",
                "out of range (allowed: 1 to 100000000)"},
        BadCase{"NameDotDot", "name = \"..\"\n" + std::string(kValid), "exp.toml:1:8",
                "'name' must be a plain file name"},
        BadCase{"NameWithSlash", "name = \"a/b\"\n" + std::string(kValid), "exp.toml:1:8",
                "'name' must be a plain file name"},
        BadCase{"UndeclaredBuild", with("\"osmesa-llvmpipe\"", "\"osmesa-llvmpipe@new\""),
                "exp.toml:2:14", "names driver build 'new', which no [builds.new] table declares"},
        BadCase{"BuildOfReference", with("\"osmesa-llvmpipe\"", "\"reference@new\"") +
                                        "[builds.new]\ndir = \"/b\"\n",
                "exp.toml:2:14", "unknown platform 'reference@new'"},
        BadCase{"BadBuildName", with("\"osmesa-llvmpipe\"", "\"osmesa-llvmpipe@a/b\""),
                "exp.toml:2:14", "unknown platform 'osmesa-llvmpipe@a/b'"},
        BadCase{"RelativeBuildDir", std::string(kValid) + "[builds.new]\ndir = \"cache/new\"\n",
                "exp.toml:12:7", "'builds.new.dir' must be an absolute path"},
        BadCase{"UnknownBuildKey", std::string(kValid) + "[builds.new]\nfolder = \"/b\"\n",
                "exp.toml:12:1", "unknown key 'builds.new.folder' (allowed: dir, origin, suite)"},
        BadCase{"TooManyShards", std::string(kValid) + "[run]\nshard_size = 1\nmax_shards = 10\n",
                "exp.toml:", "the plan has too many shards"}),
    [](const testing::TestParamInfo<BadCase>& info) { return std::string(info.param.name); });

// A build's folder: `dir` as written (~ expanded), else NAME in the build cache.
TEST(Experiment, QualifiedPlatformsDrawWithTheirDeclaredBuild) {
  const std::string text =
      with("\"osmesa-llvmpipe\"",
           "\"osmesa-llvmpipe\", \"egl-softpipe@new\", \"osmesa-llvmpipe@cached\"") +
      "[builds.new]\ndir = \"/opt/mesa-new\"\norigin = \"Debian\"\n[builds.cached]\n";
  const Experiment e = parse_experiment(text, "exp.toml");
  setenv("RENDERAUDIT_BUILD_CACHE", "/var/cache/builds", 1);
  const std::string cached = experiment_platform(e, "osmesa-llvmpipe@cached").build_dir;
  unsetenv("RENDERAUDIT_BUILD_CACHE");
  EXPECT_EQ(cached, "/var/cache/builds/cached");
  ASSERT_EQ(e.platforms.size(), 3u);
  const rundir::PlatformSpec installed = experiment_platform(e, "osmesa-llvmpipe");
  EXPECT_EQ(installed.build, "");
  EXPECT_EQ(installed.build_dir, "");
  const rundir::PlatformSpec egl = experiment_platform(e, "egl-softpipe@new");
  EXPECT_EQ(egl.backend, rundir::Backend::kEglSurfaceless);
  EXPECT_EQ(egl.mesa_driver, "softpipe");
  EXPECT_EQ(egl.build, "new");
  EXPECT_EQ(egl.build_dir, "/opt/mesa-new");
  EXPECT_EQ(e.builds.at("new").origin, "Debian");
  // the hash changes with the builds (another driver is another experiment)
  EXPECT_NE(e.hash, parse_experiment(kValid, "exp.toml").hash);
}

TEST(Experiment, ExplicitOrientationsAreRotations) {
  const Experiment e =
      parse_experiment(with("orientations = 2", "orientations = [[0, 0, 0], [90, 0, 0]]"), "x.toml");
  ASSERT_EQ(e.views.size(), 8u);
  // Yaw 90 about +Y turns the view axis -Z into -X.
  const geometry::Mat4& r = e.views[1].rotation;
  EXPECT_NEAR(-r.at(0, 2), -1.0, 1e-15);
  EXPECT_NEAR(-r.at(2, 2), 0.0, 1e-15);
}

}  // namespace
}  // namespace ra::rundir
