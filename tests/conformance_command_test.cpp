// End to end: runs of the faulty platform's conformance variants through `renderaudit run` and
// `analyze` are classified as predicted: snapping to 5 bits is measured as such and is
// never a violation; dropping every line's last pixel is within the GL rules; shifting every
// primitive by one pixel is a violation that violations.md lists and an audit against the clean
// run reports first, with a failing conformance testcase. `renderaudit conformance` turns such a
// run into a CI verdict: exit 5 with violations, JUnit, and an expectations file that makes the
// known ones pass.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "tests/cli_harness.h"

namespace fs = std::filesystem;
using namespace ra::testing_cli;

namespace {

std::string faulty_experiment(const std::string& faults,
                              const std::string& platforms = "\"faulty\"") {
  return "seed = 3\nplatforms = [" + platforms + "]\n[views]\norientations = 1\nfov_deg = [150]\n"
         "windows = [64]\nnear = 0.01\nfar = 10.0\n[primitives]\npoints = 600\nlines = 300\n"
         "triangles = 300\n[run]\nshard_size = 300\n[faults]\n" +
         faults;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Records per kind and conformance class, read as plain CSV (columns by header name).
std::map<std::string, std::map<std::string, int>> classes(const std::string& run_dir) {
  std::map<std::string, std::map<std::string, int>> out;
  for (const auto& e : fs::directory_iterator(run_dir + "/records")) {
    if (!ra::rundir::is_records_file_name(e.path().filename().string())) continue;
    std::istringstream in(ra::testing_cli::read_records_text(e.path().string()));
    std::string line;
    std::getline(in, line);
    std::vector<std::string> header;
    std::stringstream hs(line);
    for (std::string h; std::getline(hs, h, ',');) header.push_back(h);
    const auto col = [&](const char* name) {
      return std::size_t(std::find(header.begin(), header.end(), name) - header.begin());
    };
    const std::size_t kind = col("kind"), conformance = col("conformance"), status = col("status");
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#') continue;
      std::vector<std::string> cells;
      std::stringstream ls(line);
      for (std::string c; std::getline(ls, c, ',');) cells.push_back(c);
      while (cells.size() < header.size()) cells.push_back("");
      if (cells[status] == "ok") ++out[cells[kind]][cells[conformance]];
    }
  }
  return out;
}

Outcome run_variant(const std::string& dir, const std::string& faults,
                    const std::string& platforms = "\"faulty\"") {
  fs::create_directories(dir);
  write_text(dir + "/e.toml", faulty_experiment(faults, platforms));
  return run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --jobs 2");
}

TEST(ConformanceCommand, FaultyVariantsAreClassifiedAsPredicted) {
  const std::string dir = fresh_dir("conformance_variants");

  // Snapping to 5 bits, rounding to nearest: measured as that grid; never a violation.
  ASSERT_EQ(run_variant(dir + "/snap", "snap_bits = 5\n").exit_code, 0);
  const nlohmann::json driver = nlohmann::json::parse(read_text(dir + "/snap/run/drivers/faulty.json"));
  EXPECT_EQ(driver["effective_subpixel"]["text"], "5 bits, nearest") << driver.dump();
  auto c = classes(dir + "/snap/run");
  for (const auto& [kind, n] : c) {
    EXPECT_EQ(n.count("violation"), 0u) << kind;
    EXPECT_EQ(n.count("within-spec"), 0u) << kind;
  }
  EXPECT_GT(c["triangle"]["snapped"], 10);
  EXPECT_GT(c["line"]["snapped"], 10);
  ASSERT_EQ(run_renderaudit("analyze " + dir + "/snap/run").exit_code, 0);
  EXPECT_NE(read_text(dir + "/snap/run/analysis/violations.md").find("None: every one of the"),
            std::string::npos);

  // Every line drawn without its last pixel: within-spec (14.5.1 rule 2), never a violation.
  ASSERT_EQ(run_variant(dir + "/drop", "drop_line_end_fraction = 1.0\n").exit_code, 0);
  c = classes(dir + "/drop/run");
  EXPECT_EQ(c["line"].count("violation"), 0u);
  EXPECT_GT(c["line"]["within-spec"], 100);
  EXPECT_EQ(c["triangle"].size(), 1u);  // all exact
  EXPECT_GT(c["triangle"]["exact"], 0);

  // Everything one pixel to the right: triangles with pixels break the polygon rule; an audit of
  // the faulty platform against the reference (which the same run drew) puts the new violations
  // first and fails their testcase.
  ASSERT_EQ(run_variant(dir + "/shift", "shift_fraction = 1.0\n", "\"reference\", \"faulty\"")
                .exit_code,
            0);
  c = classes(dir + "/shift/run");
  EXPECT_GT(c["triangle"]["violation"], 50);
  ASSERT_EQ(run_renderaudit("analyze " + dir + "/shift/run").exit_code, 0);
  const std::string list = read_text(dir + "/shift/run/analysis/violations.md");
  EXPECT_NE(list.find("| faulty | triangle | 1 |"), std::string::npos) << list;
  EXPECT_NE(list.find("`" + std::string(RA_BINARY) + " show " + dir +
                      "/shift/run -p faulty -k triangle -v 1 -i "),
            std::string::npos) << list;

  const Outcome audit = run_renderaudit("audit " + dir + "/shift/run --between reference faulty " +
                                        "--no-history --max-rerenders 0");
  EXPECT_EQ(audit.exit_code, 1) << audit.output;  // changed
  const std::string out = dir + "/shift/run/audit-reference-vs-faulty";
  const std::string md = read_text(out + "/audit.md");
  const std::size_t first = md.find("## New conformance violations");
  ASSERT_NE(first, std::string::npos) << md;
  EXPECT_LT(first, md.find("## Drivers"));
  EXPECT_NE(md.find("reference vs faulty point, view 1 (group A), index "), std::string::npos) << md;
  EXPECT_NE(md.find(": exact -> violation ("), std::string::npos) << md;
  const std::string junit = read_text(out + "/junit.xml");
  EXPECT_NE(junit.find("name=\"conformance, group A (view 1)\""), std::string::npos) << junit;
  EXPECT_NE(junit.find("<failure type=\"violation\""), std::string::npos) << junit;
}

// The lines of an expectations file that name a primitive (comments and blank lines left out).
std::vector<std::string> listed_lines(const std::string& path) {
  std::vector<std::string> out;
  std::istringstream in(read_text(path));
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line[0] != '#') out.push_back(line);
  return out;
}

// CI on a run with violations (the faulty platform shifting 5% of its primitives one pixel):
// `run --fail-on-violations` and `conformance` fail it with exit 5 and a failing JUnit case; the
// expectations file written from the run makes it pass; a violation not listed fails again, named;
// a run of a driver that shifts fewer (a subset) passes and reports the listed ones it fixed.
TEST(ConformanceCommand, ARunWithViolationsFailsCIAndPassesWithItsExpectations) {
  const std::string dir = fresh_dir("conformance_ci");
  write_text(dir + "/e.toml", faulty_experiment("shift_fraction = 0.05\n"));
  const Outcome run = run_renderaudit("run " + dir + "/e.toml --out " + dir +
                                      "/run --jobs 2 --quiet --fail-on-violations");
  EXPECT_EQ(run.exit_code, 5) << run.output;
  EXPECT_NE(run.output.find("conformance: FAIL: "), std::string::npos) << run.output;

  const std::string r = dir + "/run";
  const Outcome ci = run_renderaudit("conformance " + r + " --junit " + dir + "/junit.xml");
  EXPECT_EQ(ci.exit_code, 5) << ci.output;
  EXPECT_NE(ci.output.find("new: faulty "), std::string::npos) << ci.output;
  EXPECT_NE(ci.output.find(" show " + r + " -p faulty -k "), std::string::npos) << ci.output;
  const std::string junit = read_text(dir + "/junit.xml");
  EXPECT_NE(junit.find("<testcase classname=\"renderaudit.conformance.faulty.triangle\" "
                       "name=\"view 1 (150 deg, 64x64)\""),
            std::string::npos) << junit;
  EXPECT_NE(junit.find("<failure type=\"violation\""), std::string::npos) << junit;

  // Written from the run: one line per violation, PLATFORM KIND VIEW INDEX, sorted; exit 0.
  const std::string known = dir + "/known.txt";
  const Outcome wrote = run_renderaudit("conformance " + r + " --write-expectations " + known);
  EXPECT_EQ(wrote.exit_code, 0) << wrote.output;
  const std::vector<std::string> lines = listed_lines(known);
  ASSERT_GE(lines.size(), 3u) << read_text(known);
  const std::regex form(R"(faulty (point|line|triangle) 1 \d+  # \d+ px: [a-z, -]+)");
  for (const std::string& l : lines) EXPECT_TRUE(std::regex_match(l, form)) << l;
  EXPECT_NE(wrote.output.find("expectations: " + std::to_string(lines.size()) +
                              " violations written to " + known),
            std::string::npos) << wrote.output;

  const Outcome pass = run_renderaudit("conformance " + r + " --expectations " + known +
                                       " --junit " + dir + "/pass.xml");
  EXPECT_EQ(pass.exit_code, 0) << pass.output;
  EXPECT_NE(pass.output.find("conformance: PASS: every violation is listed in " + known),
            std::string::npos) << pass.output;
  EXPECT_EQ(read_text(dir + "/pass.xml").find("<failure"), std::string::npos);
  EXPECT_NE(read_text(dir + "/pass.xml").find("known (" + known + ":"), std::string::npos);

  // One violation taken off the list: new again, named, exit 5.
  std::string fewer = read_text(known);
  const std::string dropped = lines.back().substr(0, lines.back().find("  #"));
  fewer.erase(fewer.find(lines.back()), lines.back().size() + 1);
  write_text(dir + "/fewer.txt", fewer);
  const Outcome fresh = run_renderaudit("conformance " + r + " --expectations " + dir +
                                        "/fewer.txt");
  EXPECT_EQ(fresh.exit_code, 5) << fresh.output;
  EXPECT_NE(fresh.output.find("new: " + dropped + ": "), std::string::npos) << fresh.output;
  EXPECT_NE(fresh.output.find("conformance: FAIL: 1 violation not listed in " + dir +
                              "/fewer.txt"),
            std::string::npos) << fresh.output;

  // A driver that shifts fewer primitives (a subset of these): what it no longer breaks is
  // reported as fixed, with the line to remove; it passes unless --fail-on-fixed.
  write_text(dir + "/better.toml", faulty_experiment("shift_fraction = 0.01\n"));
  ASSERT_EQ(run_renderaudit("run " + dir + "/better.toml --out " + dir + "/better --jobs 2 --quiet")
                .exit_code, 0);
  const Outcome better =
      run_renderaudit("conformance " + dir + "/better --expectations " + known);
  EXPECT_EQ(better.exit_code, 0) << better.output;
  EXPECT_NE(better.output.find("fixed: faulty "), std::string::npos) << better.output;
  EXPECT_TRUE(std::regex_search(better.output,
                                std::regex(" is now (exact|snapped|within-spec): remove its line")))
      << better.output;
  EXPECT_NE(better.output.find("(" + known + ":"), std::string::npos) << better.output;
  EXPECT_EQ(run_renderaudit("conformance " + dir + "/better --expectations " + known +
                            " --fail-on-fixed").exit_code, 5);

  // Malformed and stale lines: each said with its place, exit 2, nothing judged.
  write_text(dir + "/bad.txt",
             "# known\nfaulty point 1\nfaulty pointy 1 2\nnosuch point 1 2\n"
             "faulty point 9 2\nfaulty point 1 600\n" + lines.front() + "\n" + lines.front() + "\n");
  const Outcome malformed =
      run_renderaudit("conformance " + r + " --expectations " + dir + "/bad.txt");
  EXPECT_EQ(malformed.exit_code, 2) << malformed.output;
  for (const std::string& at : {":2: expected four fields", ":3: kind 'pointy'", ":8: faulty "})
    EXPECT_NE(malformed.output.find(dir + "/bad.txt" + at), std::string::npos) << malformed.output;
  EXPECT_EQ(malformed.output.find("conformance: "), std::string::npos) << malformed.output;
  write_text(dir + "/stale.txt", "nosuch point 1 2\nfaulty point 9 2\nfaulty point 1 600\n");
  const Outcome stale =
      run_renderaudit("conformance " + r + " --expectations " + dir + "/stale.txt");
  EXPECT_EQ(stale.exit_code, 2) << stale.output;
  for (const std::string& at : {":1: platform 'nosuch' is not in the experiment of ",
                                ":2: view 9 is not in the experiment of ",
                                ":3: index 600 is past the 600 points per view"})
    EXPECT_NE(stale.output.find(dir + "/stale.txt" + at), std::string::npos) << stale.output;
  // run reads the file before it draws: a malformed one stops it with nothing written
  const Outcome refused = run_renderaudit("run " + dir + "/e.toml --out " + dir +
                                          "/never --quiet --expectations " + dir + "/bad.txt");
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_FALSE(fs::exists(dir + "/never"));
}

}  // namespace
