// End to end: figures that show their finding. One run of llvmpipe and softpipe triangles in four
// view groups (FOV 30 and 150, windows 128 and 907) is plotted once:
//   - the conformance bars show the share that differs from the reference rasterizer (small),
//     checked against a count over the records, on an axis zoomed to the largest bar;
//   - box plots of a metric whose view groups differ tenfold in spread (TEs-norm: the 907 x 907
//     groups' normalised errors are about 50 times smaller) get an axis per group;
//   - the percentages of a bar figure share one number of decimals;
//   - a box plot's title says what varies in it (view group, platform) and a single box is
//     "Box plot of".
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <set>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli_harness.h"

namespace fs = std::filesystem;
using namespace ra::testing_cli;

namespace {

// The cells of one CSV line; a cell in double quotes may hold commas ("" is one quote).
std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      cells.back() += '"', ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      cells.emplace_back();
    } else {
      cells.back() += c;
    }
  }
  return cells;
}

// Per (platform, view group) of the triangle records with status ok: {records, ref_diff > 0}.
std::map<std::pair<std::string, std::string>, std::pair<int, int>> differing_share(
    const std::string& run) {
  std::map<std::pair<std::string, std::string>, std::pair<int, int>> out;
  for (const auto& e : fs::directory_iterator(run + "/records")) {
    if (e.path().filename().string().find(".triangle.") == std::string::npos) continue;
    std::istringstream text(read_records_text(e.path().string()));
    std::string line;
    std::getline(text, line);
    const std::vector<std::string> header = split(line);
    std::map<std::string, std::size_t> at;
    for (std::size_t i = 0; i < header.size(); ++i) at[header[i]] = i;
    while (std::getline(text, line)) {
      if (line.empty() || line[0] == '#') continue;
      const std::vector<std::string> c = split(line);
      if (c.at(at.at("status")) != "ok" || c.at(at.at("ref_diff")).empty()) continue;
      const std::string group(1, char('A' + std::stoi(c.at(at.at("view_group")))));
      auto& [n, differs] = out[{c.at(at.at("platform")), group}];
      ++n;
      differs += std::stoll(c.at(at.at("ref_diff"))) > 0;
    }
  }
  return out;
}

// The figures of the run, made once: their index (figures/index.json) by figure id.
const std::map<std::string, nlohmann::json>& plotted(std::string* run_dir) {
  static std::string run;
  static const std::map<std::string, nlohmann::json> figures = [] {
    ::unsetenv("DISPLAY");
    const std::string dir = fresh_dir("figure_findings");
    write_text(dir + "/e.toml",
               "name = \"findings\"\nseed = 4\n"
               "platforms = [\"osmesa-llvmpipe\", \"osmesa-softpipe\"]\n[views]\norientations = 1\n"
               "fov_deg = [30, 150]\nwindows = [128, 907]\nnear = 0.01\nfar = 10.0\n"
               "[primitives]\npoints = 0\nlines = 0\ntriangles = 300\n");
    run = dir + "/run";
    EXPECT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + run + " -q --brief").exit_code, 0);
    EXPECT_EQ(run_renderaudit("analyze " + run + " --quiet").exit_code, 0);
    const Outcome plot = run_renderaudit("plot " + run);
    EXPECT_EQ(plot.exit_code, 0) << plot.output;
    std::map<std::string, nlohmann::json> by_id;
    const nlohmann::json index =
        nlohmann::json::parse(read_records_text(run + "/figures/index.json"));
    for (const auto& f : index.at("figures")) by_id[f.at("id").get<std::string>()] = f;
    return by_id;
  }();
  *run_dir = run;
  return figures;
}

}  // namespace

TEST(FigureFindings, ConformanceBarsShowTheShareThatDiffersOnAnAxisOfItsOwnSize) {
  std::string run;
  const auto& figures = plotted(&run);

  const auto expected = differing_share(run);
  ASSERT_FALSE(expected.empty());
  const std::string csv = run + "/figures/conformance.triangle.csv";
  std::istringstream rows(read_records_text(csv));
  std::string line;
  std::getline(rows, line);
  EXPECT_EQ(line, "category,series,value,label");
  double largest = 0;
  int checked = 0;
  while (std::getline(rows, line)) {
    const std::vector<std::string> c = split(line);
    ASSERT_GE(c.size(), 4u) << line;
    const std::string group = c[0].substr(0, 1);
    const std::string series = c[1];
    if (series.find(", all cases") == std::string::npos) continue;
    const std::string platform = series.substr(0, series.find(','));
    const auto [n, differs] = expected.at({platform, group});
    const double value = std::stod(c[2]);
    EXPECT_NEAR(value, 100.0 * differs / n, 1e-9) << line;
    largest = std::max(largest, value);
    ++checked;
  }
  EXPECT_EQ(checked, 8);  // 2 platforms x 4 view groups
  ASSERT_GT(largest, 0);
  ASSERT_LT(largest, 50);  // the finding is a small share: the axis must not run to 100

  ASSERT_TRUE(figures.count("conformance.triangle"));
  const nlohmann::json& f = figures.at("conformance.triangle");
  const double top = f.at("layout").at("y_max").get<double>();
  EXPECT_GE(top, largest);
  EXPECT_LE(top, 2 * largest + 1) << "the axis is not zoomed to the bars";
  EXPECT_NE(f.at("title").get<std::string>().find("differ from the reference rasterizer"), std::string::npos);
}

TEST(FigureFindings, BoxPlotsOfGroupsTenfoldApartGetAnAxisEach) {
  std::string run;
  const auto& figures = plotted(&run);
  EXPECT_FALSE(figures.count("boxplot.triangle.te_s_norm"));  // no shared axis
  for (const char* g : {"a", "b", "c", "d"}) {  // view groups A-D (figure ids are lower case)
    const std::string id = std::string("boxplot.triangle.te_s_norm.") + g;
    ASSERT_TRUE(figures.count(id)) << id;
    const nlohmann::json& f = figures.at(id);
    EXPECT_NE(f.at("caption").get<std::string>().find("One figure per view group"),
              std::string::npos);
    // the axis covers this group's boxes only: its CSV's whiskers lie within it, and fill a
    // good part of it
    std::istringstream rows(read_records_text(run + "/figures/" + id + ".csv"));
    std::string line;
    std::getline(rows, line);
    const std::vector<std::string> header = split(line);
    const auto col = [&](const char* name) {
      return std::size_t(std::find(header.begin(), header.end(), name) - header.begin());
    };
    double lo = 1e300, hi = -1e300;
    while (std::getline(rows, line)) {
      const std::vector<std::string> c = split(line);
      lo = std::min(lo, std::stod(c.at(col("lower_whisker"))));
      hi = std::max(hi, std::stod(c.at(col("upper_whisker"))));
    }
    const double y_min = f.at("layout").at("y_min"), y_max = f.at("layout").at("y_max");
    EXPECT_LE(y_min, lo) << id;
    EXPECT_GE(y_max, hi) << id;
    EXPECT_GT(hi - lo, 0.3 * (y_max - y_min)) << id << ": the boxes are flat on their own axis";
  }
}

namespace {

// Decimals of a label ("38.00": 2; "<0.01": 2; "0": 0).
int decimals(const std::string& label) {
  const auto dot = label.find('.');
  return dot == std::string::npos ? 0 : int(label.size() - dot - 1);
}

// The cells of a figure's CSV, by column name, row by row.
std::vector<std::map<std::string, std::string>> figure_rows(const std::string& csv) {
  std::istringstream text(read_records_text(csv));
  std::string line;
  std::getline(text, line);
  const std::vector<std::string> header = split(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(text, line)) {
    const std::vector<std::string> c = split(line);
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < c.size(); ++i) row[header[i]] = c[i];
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

TEST(FigureFindings, ABarFigureWritesItsPercentagesOneWay) {
  std::string run;
  const auto& figures = plotted(&run);
  for (const char* id : {"conformance.triangle", "conformance.overview"}) {
    ASSERT_TRUE(figures.count(id)) << id;
    int checked = 0, places = -1;
    for (const auto& row : figure_rows(run + "/figures/" + id + ".csv")) {
      const std::string& label = row.at("label");
      if (label == "0" || label == "n/a") continue;  // none at all; nothing compared
      if (places < 0) places = decimals(label);
      EXPECT_EQ(decimals(label), places) << id << ": " << label;
      ++checked;
    }
    EXPECT_GE(checked, 4) << id;
  }
}

TEST(FigureFindings, ABoxPlotIsTitledForWhatVariesInIt) {
  std::string run;
  const auto& figures = plotted(&run);
  int checked = 0;
  for (const auto& [id, f] : figures) {
    if (f.at("kind") != "boxplot") continue;
    std::set<std::string> categories, platforms;
    const auto rows = figure_rows(run + "/figures/" + id + ".csv");
    for (const auto& row : rows)
      categories.insert(row.at("category")), platforms.insert(row.at("series"));
    const std::string title = f.at("title");
    const std::string by = categories.size() > 1 && platforms.size() > 1
                               ? " by view group and platform:"
                           : categories.size() > 1 ? " by view group:"
                           : platforms.size() > 1  ? " by platform:"
                                                   : ":";
    EXPECT_EQ(title.rfind(rows.size() == 1 ? "Box plot of " : "Box plots of ", 0), 0u) << title;
    EXPECT_NE(title.find(by), std::string::npos) << title << " (" << rows.size() << " boxes)";
    ++checked;
  }
  EXPECT_GE(checked, 5);
}
