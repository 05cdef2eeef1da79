// Scatter figures without drawing: the CSV beside a scatter figure holds exactly the numbers drawn,
// the note names the points a log axis cannot place, and the plots stage turns figures.json's
// speed_error points into one speed-against-error figure per kind.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "analysis/run_analysis.h"
#include "stats/csv_table.h"
#include "analysis/records_testing.h"
#include "plots/figure.h"
#include "plots/plot_run.h"

namespace ra::plots {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Why: the CSV is how a figure is checked or redrawn with another tool; %.17g must give back the
// same doubles, empty cells mean "no bar", and a label with a comma stays one cell.
TEST(ScatterFigure, CsvRoundTripsExactNumbers) {
  ScatterContent c;
  c.x_log10 = c.y_log10 = true;
  ScatterSeries a;
  a.name = "osmesa-llvmpipe";
  a.x = {1.0 / 3, 12345.678901234567};
  a.y = {0.1, 2.5e-7};
  a.labels = {"A", "B, wide"};
  a.x_lo = {0.2, 1e4};
  a.x_hi = {0.5, 2e4};
  a.y_lo = {0.05, 1e-7};
  a.y_hi = {0.3, 5e-7};
  ScatterSeries b;
  b.name = "osmesa-llvmpipe-msaa4";
  b.x = {std::nextafter(1.0, 2.0)};
  b.y = {0};
  b.labels = {"A"};  // no bars
  c.series = {a, b};
  Figure f;
  f.id = "scatter_csv";
  f.content = c;
  EXPECT_STREQ(figure_kind_name(f), "scatter");
  const ra::analysis::testing::ScopedTempDir dir("scatter_csv");
  const std::string path = (dir.path / "s.csv").string();
  write_figure_data(f, path);
  const auto t = stats::CsvTable::read_file(path);
  EXPECT_EQ(t.header(), (std::vector<std::string>{"series", "label", "x", "y", "x_lo", "x_hi",
                                                  "y_lo", "y_hi"}));
  ASSERT_EQ(t.row_count(), 3u);
  EXPECT_EQ(t.numeric_column("x").values,
            (std::vector<double>{1.0 / 3, 12345.678901234567, std::nextafter(1.0, 2.0)}));
  EXPECT_EQ(t.numeric_column("y").values, (std::vector<double>{0.1, 2.5e-7, 0}));
  EXPECT_EQ(t.numeric_column("x_lo").values, (std::vector<double>{0.2, 1e4}));
  EXPECT_EQ(t.numeric_column("x_lo").n_missing, 1u);
  EXPECT_EQ(t.numeric_column("y_hi").values, (std::vector<double>{0.3, 5e-7}));
  EXPECT_EQ(t.cell(1, t.column("label")), "B, wide");
  EXPECT_EQ(t.cell(2, t.column("series")), "osmesa-llvmpipe-msaa4");
}

// Why: log10(0) does not exist; a point that cannot be placed must be named, not silently lost.
TEST(ScatterFigure, NoteNamesPointsALogAxisCannotPlace) {
  ScatterContent c;
  c.series = {{"p1", {1, 2}, {0.5, 0}, {"A", "B"}, {}, {}, {}, {}},
              {"p2", {-1, 3}, {0.5, 1}, {"A", "B"}, {}, {}, {}, {}}};
  EXPECT_EQ(scatter_omitted_note(c), "");  // linear axes place everything
  c.y_log10 = true;
  EXPECT_EQ(scatter_omitted_note(c),
            "1 point not drawn: a zero or negative value cannot be placed on a log axis: B p1 "
            "(y = 0).");
  c.x_log10 = true;
  EXPECT_EQ(scatter_omitted_note(c),
            "2 points not drawn: a zero or negative value cannot be placed on a log axis: B p1 "
            "(y = 0), A p2 (x = -1).");
}

// Points of two platforms in views 1-4 (groups A, B) with times; the second platform is slower.
std::vector<metrics::Record> small_run() {
  std::vector<metrics::Record> rs;
  std::uint64_t i = 0;
  for (const std::string platform : {"plat-a", "plat-b"})
    for (int view = 1; view <= 4; ++view)
      for (int k = 0; k < 20; ++k) {
        metrics::Record r =
            ra::analysis::testing::point(platform, view, i++, 0.05 * (k + 1) * view);
        r.render_us = (platform == "plat-a" ? 1 : 10) * (k + 1.0);
        r.batch_size = 4;
        rs.push_back(r);
      }
  return rs;
}

// Why: the plot stage must draw exactly figures.json's numbers: one point per platform x view
// group at (median_us, median_error x 10^3 as the tables show PEnorm), IQR bars from the
// quartiles, log axes, in the kind's section, under the id speed_error.<kind>.
TEST(ScatterFigure, PlanHasOneSpeedErrorFigurePerKindWithTheAnalysisNumbers) {
  const ra::analysis::testing::ScopedTempDir scoped("speed_error_plan");
  ra::analysis::testing::write_records(scoped.path, small_run());
  ra::analysis::AnalyzeOptions o;
  o.run_dir = scoped.path.string();
  ra::analysis::analyze_run(o);
  const json doc = json::parse(
      ra::analysis::testing::read_text(scoped.path / "analysis" / "figures.json"));
  const FigurePlan plan = plan_figures(scoped.path.string());
  const auto it = std::find_if(plan.figures.begin(), plan.figures.end(),
                               [](const Figure& f) { return f.id == "speed_error.point"; });
  ASSERT_NE(it, plan.figures.end());
  EXPECT_EQ(it->section, "points");
  EXPECT_NE(it->title.find("plat-a, plat-b"), std::string::npos) << it->title;
  EXPECT_NE(it->title.find("PEnorm"), std::string::npos) << it->title;
  EXPECT_NE(it->y_label.find("x 10^3"), std::string::npos) << it->y_label;
  EXPECT_NE(it->caption.find("batch_size"), std::string::npos);
  const auto& c = std::get<ScatterContent>(it->content);
  EXPECT_TRUE(c.x_log10 && c.y_log10);
  ASSERT_EQ(c.series.size(), 2u);
  const json& points = doc["speed_error"][0]["points"];
  ASSERT_EQ(points.size(), 4u);
  std::size_t k = 0;
  for (const ScatterSeries& s : c.series) {
    ASSERT_EQ(s.x.size(), 2u);
    EXPECT_EQ(s.labels, (std::vector<std::string>{"A", "B"}));
    for (std::size_t i = 0; i < s.x.size(); ++i, ++k) {
      const json& p = points[k];
      EXPECT_EQ(p["platform"], s.name);
      EXPECT_EQ(s.x[i], p["median_us"].get<double>());
      EXPECT_EQ(s.x_lo[i], p["q1_us"].get<double>());
      EXPECT_EQ(s.x_hi[i], p["q3_us"].get<double>());
      EXPECT_DOUBLE_EQ(s.y[i], p["median_error"].get<double>() * 1e3);
      EXPECT_DOUBLE_EQ(s.y_lo[i], p["q1_error"].get<double>() * 1e3);
      EXPECT_DOUBLE_EQ(s.y_hi[i], p["q3_error"].get<double>() * 1e3);
    }
  }
  // times 1..20 us (plat-a) and 10..200 us (plat-b): medians 10.5 and 105 in both groups
  EXPECT_DOUBLE_EQ(c.series[0].x[0], 10.5);
  EXPECT_DOUBLE_EQ(c.series[1].x[1], 105);
}

}  // namespace
}  // namespace ra::plots
