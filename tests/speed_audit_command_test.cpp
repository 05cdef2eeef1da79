// End-to-end tests of `renderaudit audit --speed`: drawing time judged per kind and view group,
// with the `faulty` platform's [faults] slowdown as a driver made slower on purpose (no pixel
// changes), and A/A comparisons (one build drawn as two platforms; one experiment run twice) that
// must never be called faster or slower.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>

#include "audit/history_db.h"
#include "tests/cli_harness.h"

namespace fs = std::filesystem;
using namespace ra::testing_cli;

namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// A build folder of the faulty platform whose [faults] table is `faults`.
void faulty_build(const std::string& dir, const std::string& faults) {
  fs::create_directories(dir);
  write_text(dir + "/faults.toml", "[faults]\n" + faults);
}

// platforms: faulty (timed, not slowed), faulty@slow (triangles 30% slower), faulty@same (timed,
// not slowed: the same build as faulty under another name). 256 x 256 window: the reference
// rasterizer's triangles take microseconds, not nanoseconds.
std::string experiment(const std::string& dir, const std::string& platforms) {
  return "seed = 5\nplatforms = [" + platforms +
         "]\n[views]\norientations = 1\nfov_deg = [150]\nwindows = [256]\nnear = 0.01\n"
         "far = 10.0\n[primitives]\npoints = 60\nlines = 60\ntriangles = 60\n"
         "[faults]\nslowdown = 0\n[builds.slow]\ndir = \"" +
         dir + "/slow\"\n[builds.same]\ndir = \"" + dir + "/same\"\n";
}

// kind -> verdict of the audit's speed rows of one pair.
std::map<std::string, std::string> verdicts(const nlohmann::json& audit) {
  std::map<std::string, std::string> out;
  for (const auto& row : audit.at("speed")) out[row.at("kind")] = row.at("verdict");
  return out;
}

class SpeedAudit : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fresh_dir("speed_audit");
    faulty_build(dir_ + "/slow", "slowdown = 0.3\nslowdown_kinds = [\"triangle\"]\n");
    faulty_build(dir_ + "/same", "slowdown = 0\n");
    write_text(dir_ + "/e.toml",
               experiment(dir_, "\"faulty\", \"faulty@slow\", \"faulty@same\""));
    const Outcome run = run_renderaudit("run " + dir_ + "/e.toml --out " + dir_ +
                                        "/run --jobs 2 --quiet");
    ASSERT_EQ(run.exit_code, 0) << run.output;
  }
  std::string dir_;
};

TEST_F(SpeedAudit, ABuildThirtyPercentSlowerOnTrianglesIsSlowerForTrianglesOnly) {
  const Outcome o = run_renderaudit("audit " + dir_ + "/run --between faulty faulty@slow --speed " +
                                    "--speed-primitives 60 --speed-repeats 3 --no-history");
  // no pixel changed, but drawing time did: changed (exit 1)
  ASSERT_EQ(o.exit_code, 1) << o.output;
  EXPECT_NE(o.output.find("no primitive changed, but drawing time did"), std::string::npos)
      << o.output;
  const nlohmann::json j =
      nlohmann::json::parse(read_text(dir_ + "/run/audit-faulty-vs-faulty@slow/audit.json"));
  EXPECT_EQ(j.at("schema_version"), 2);
  EXPECT_EQ(j.at("counts").at("changed"), 0);
  ASSERT_EQ(j.at("speed").size(), 3u) << j.at("speed").dump(1);
  const auto v = verdicts(j);
  EXPECT_EQ(v.at("triangle"), "slower") << j.at("speed").dump(1);
  for (const char* kind : {"point", "line"})
    EXPECT_TRUE(v.at(kind) == "same" || v.at(kind) == "unknown") << kind << ": " << j.dump(1);
  for (const auto& row : j.at("speed")) {
    EXPECT_EQ(row.at("platform"), "faulty@slow");
    EXPECT_EQ(row.at("baseline_platform"), "faulty");
    EXPECT_EQ(row.at("group"), "A");
    EXPECT_EQ(row.at("n"), 60);
    // At least the slowdown (the busy wait ends on the first clock reading past its end, later
    // on a loaded machine: no upper bound).
    if (row.at("kind") == "triangle") {
      EXPECT_GT(row.at("high").get<double>(), 1.3 * 0.97);
    }
  }
  const std::string md = read_text(dir_ + "/run/audit-faulty-vs-faulty@slow/audit.md");
  EXPECT_NE(md.find("## Drawing time"), std::string::npos);
  const std::string junit = read_text(dir_ + "/run/audit-faulty-vs-faulty@slow/junit.xml");
  EXPECT_NE(junit.find("<failure type=\"slower\""), std::string::npos) << junit;

  // --speed-warn-only: the same finding, a warning, exit 0
  const Outcome warn = run_renderaudit("audit " + dir_ + "/run --between faulty faulty@slow " +
                                       "--speed --speed-primitives 60 --speed-warn-only " +
                                       "--no-history --out " + dir_ + "/warn");
  EXPECT_EQ(warn.exit_code, 0) << warn.output;
  EXPECT_NE(warn.output.find("--speed-warn-only"), std::string::npos) << warn.output;
}

TEST_F(SpeedAudit, OneBuildDrawnAsTwoPlatformsIsNeitherFasterNorSlower) {
  const Outcome o = run_renderaudit("audit " + dir_ + "/run --between faulty faulty@same --speed " +
                                    "--speed-primitives 60 --no-history");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const nlohmann::json j =
      nlohmann::json::parse(read_text(dir_ + "/run/audit-faulty-vs-faulty@same/audit.json"));
  ASSERT_EQ(j.at("speed").size(), 3u);
  for (const auto& [kind, verdict] : verdicts(j))
    EXPECT_TRUE(verdict == "same" || verdict == "unknown") << kind << ": " << j.dump(1);
}

TEST_F(SpeedAudit, ARunAgainstARerunIsNeitherFasterNorSlowerAndTheHistoryKeepsIt) {
  write_text(dir_ + "/one.toml", experiment(dir_, "\"faulty\""));
  for (const char* run : {"/base", "/cur"})
    ASSERT_EQ(run_renderaudit("run " + dir_ + "/one.toml --out " + dir_ + run +
                              " --jobs 2 --quiet")
                  .exit_code,
              0);
  const Outcome o = run_renderaudit("audit " + dir_ + "/base " + dir_ + "/cur --speed " +
                                    "--speed-primitives 60 --db " + dir_ + "/h.sqlite");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const nlohmann::json j = nlohmann::json::parse(read_text(dir_ + "/cur/audit/audit.json"));
  for (const auto& [kind, verdict] : verdicts(j))
    EXPECT_TRUE(verdict == "same" || verdict == "unknown") << kind << ": " << j.dump(1);
  const std::vector<ra::audit::HistoryEntry> h = ra::audit::read_history(dir_ + "/h.sqlite");
  ASSERT_EQ(h.size(), 1u);
  ASSERT_EQ(h[0].summary.speed.size(), 3u);
  EXPECT_EQ(h[0].summary.speed[0].platform, "faulty");
  EXPECT_EQ(h[0].summary.speed[0].view_group, 1);
  EXPECT_EQ(h[0].summary.speed[0].n, 60);
  EXPECT_GT(h[0].summary.speed[0].current_median_us, 0);
}

TEST(SpeedAuditInput, ABadSlowdownIsALocatedError) {
  const std::string dir = fresh_dir("speed_audit_input");
  write_text(dir + "/bad.toml",
             "seed = 1\nplatforms = [\"faulty\"]\n[views]\norientations = 1\nfov_deg = [30]\n"
             "windows = [32]\nnear = 0.01\nfar = 10.0\n[primitives]\npoints = 1\n[faults]\n"
             "slowdown = -0.5\n");
  const Outcome o = run_renderaudit("run " + dir + "/bad.toml --out " + dir + "/run");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("bad.toml:12:12: "), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("'faults.slowdown' out of range (allowed: 0 to 100"), std::string::npos)
      << o.output;
  EXPECT_FALSE(fs::exists(dir + "/run"));
  write_text(dir + "/kinds.toml",
             "seed = 1\nplatforms = [\"faulty\"]\n[views]\norientations = 1\nfov_deg = [30]\n"
             "windows = [32]\nnear = 0.01\nfar = 10.0\n[primitives]\npoints = 1\n[faults]\n"
             "slowdown = 0.5\nslowdown_kinds = [\"quad\"]\n");
  const Outcome k = run_renderaudit("run " + dir + "/kinds.toml --out " + dir + "/run2");
  EXPECT_EQ(k.exit_code, 2) << k.output;
  EXPECT_NE(k.output.find("'faults.slowdown_kinds': not a kind (allowed: point, line, triangle)"),
            std::string::npos)
      << k.output;
}

}  // namespace
