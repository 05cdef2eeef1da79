// End to end: runs of the faulty platform's conformance variants through `renderaudit run` and
// `analyze` are classified as predicted: snapping to 5 bits is measured as such and is
// never a violation; dropping every line's last pixel is within the GL rules; shifting every
// primitive by one pixel is a violation that violations.md lists and an audit against the clean
// run reports first, with a failing conformance testcase.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
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

}  // namespace
