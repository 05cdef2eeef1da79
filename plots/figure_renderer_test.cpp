// FigureRenderer: figures are drawn where their data say, and the numbers beside them are the
// numbers drawn. Each test reads back what was written (PNG through vtkPNGReader, the CSV beside
// it, the PDF through pdftotext) rather than checking that files exist.
#include "plots/figure_renderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>

#include "stats/csv_table.h"
#include "stats/distribution_plots.h"
#include "plots/figure_builders.h"
#include "plots/figure_planner.h"
#include "plots/headless_display.h"
#include "tests/cli_harness.h"

namespace ra::plots {
namespace {

using ra::testing_cli::shell_output;
using ra::testing_cli::squeeze;

namespace fs = std::filesystem;

std::string temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("renderaudit_plots_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d.string();
}


// One display and one render window for the whole suite: a private Xvfb when there is no
// DISPLAY (CI has none), exactly what `renderaudit plot` does.
class RendererTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    display_ = std::make_unique<HeadlessDisplay>();
    renderer_ = std::make_unique<FigureRenderer>();
  }
  static void TearDownTestSuite() {
    renderer_.reset();
    display_.reset();
  }
  static std::unique_ptr<HeadlessDisplay> display_;
  static std::unique_ptr<FigureRenderer> renderer_;
};
std::unique_ptr<HeadlessDisplay> RendererTest::display_;
std::unique_ptr<FigureRenderer> RendererTest::renderer_;

bool near_color(const unsigned char* p, const unsigned char c[3], int tol) {
  return std::abs(p[0] - c[0]) <= tol && std::abs(p[1] - c[1]) <= tol &&
         std::abs(p[2] - c[2]) <= tol;
}

// Why: Fig. 4's reading is "points on the 45-degree line mean equal distributions"; a Q-Q plot of
// a sample against itself must put every marker on the diagonal of the (square, equal-range) plot.
TEST_F(RendererTest, QQPlotOfIdenticalSamplesHasItsMarkersOnTheDiagonal) {
  std::vector<double> s;
  for (int i = 0; i < 400; ++i) s.push_back(0.7071 * std::pow((i + 0.5) / 400.0, 0.7));
  const Figure f = qq_figure("qq_identical", "Q-Q plot: PE, test platform, view 1 vs view 2",
                             "PE (px)", "view 1", "view 2", ra::stats::qq_plot(s, s), s.size(),
                             s.size());
  const std::string dir = temp_dir("qq");
  const RenderedFigure r = renderer_->render(f, dir + "/qq_identical");
  const FigureLayout& L = r.layout;
  ASSERT_GT(L.plot_right, L.plot_left);
  ASSERT_GT(L.plot_bottom, L.plot_top);
  EXPECT_DOUBLE_EQ(L.x_min, L.y_min);
  EXPECT_DOUBLE_EQ(L.x_max, L.y_max);

  const RgbImage img = read_png(r.png);
  ASSERT_EQ(img.width, L.width);
  ASSERT_EQ(img.height, L.height);
  unsigned char marker[3];
  series_color(0, marker);
  std::size_t marker_pixels = 0;
  double worst = 0;
  for (int y = int(L.plot_top) + 1; y < int(L.plot_bottom); ++y)
    for (int x = int(L.plot_left) + 1; x < int(L.plot_right); ++x) {
      if (!near_color(img.at(x, y), marker, 12)) continue;
      ++marker_pixels;
      // Pixel centre -> data coordinates.
      const double dx = L.x_min + (x + 0.5 - L.plot_left) / (L.plot_right - L.plot_left) *
                                      (L.x_max - L.x_min);
      const double dy = L.y_max - (y + 0.5 - L.plot_top) / (L.plot_bottom - L.plot_top) *
                                      (L.y_max - L.y_min);
      worst = std::max(worst, std::fabs(dx - dy));
    }
  EXPECT_GT(marker_pixels, 400u);  // hundreds of markers of ~50 pixels each
  // A marker has a radius of 4 px: its pixels are within about 2 x 5 px of the diagonal.
  const double px = (L.x_max - L.x_min) / (L.plot_right - L.plot_left);
  EXPECT_LT(worst, 10 * px);

  // The data beside the figure are the quantiles: x == y row by row.
  const auto table = stats::CsvTable::read_file(r.csv);
  const auto xs = table.numeric_column("x").values, ys = table.numeric_column("y").values;
  ASSERT_EQ(xs.size(), s.size());
  for (std::size_t i = 0; i < xs.size(); ++i) EXPECT_EQ(xs[i], ys[i]);
}

// Why: a Q-Q plot of two different samples must put its markers off the diagonal (the test above
// would pass for a picture that draws the diagonal in the marker colour).
TEST_F(RendererTest, QQPlotOfShiftedSamplesIsOffTheDiagonal) {
  std::vector<double> a, b;
  for (int i = 0; i < 200; ++i) a.push_back(i * 0.01), b.push_back(i * 0.01 + 0.5);
  const Figure f = qq_figure("qq_shifted", "Q-Q plot: shifted", "value (px)", "a", "b",
                             ra::stats::qq_plot(a, b), a.size(), b.size());
  const RenderedFigure r = renderer_->render(f, temp_dir("qq2") + "/qq_shifted");
  const RgbImage img = read_png(r.png);
  const FigureLayout& L = r.layout;
  unsigned char marker[3];
  series_color(0, marker);
  double sum = 0;
  std::size_t n = 0;
  for (int y = int(L.plot_top) + 1; y < int(L.plot_bottom); ++y)
    for (int x = int(L.plot_left) + 1; x < int(L.plot_right); ++x)
      if (near_color(img.at(x, y), marker, 12)) {
        const double dx = L.x_min + (x + 0.5 - L.plot_left) / (L.plot_right - L.plot_left) *
                                        (L.x_max - L.x_min);
        const double dy = L.y_max - (y + 0.5 - L.plot_top) / (L.plot_bottom - L.plot_top) *
                                        (L.y_max - L.y_min);
        sum += dy - dx;
        ++n;
      }
  ASSERT_GT(n, 100u);
  EXPECT_NEAR(sum / double(n), 0.5, 0.03);
}

// Why: the relative bihistogram's heights are densities (count / (n * width)) of each sample on
// common bins, so samples of different sizes compare; checked against hand-computed values.
TEST_F(RendererTest, BihistogramHasTheExpectedBarHeights) {
  // Common bins span [0, 2] (min and max of both): [0, 1) and [1, 2]. Upper: 4 values -> 3 and
  // 1; lower: 2 values -> 1 and 1.
  const std::vector<double> upper = {0.0, 0.2, 0.3, 1.5}, lower = {0.5, 2.0};
  ra::stats::BihistogramOptions opt;
  opt.bins = 2;
  const Figure f = bihistogram_figure("bihist", "Relative bihistogram: test", "PE (px)",
                                      "platform I, view A", "platform II, view A",
                                      ra::stats::relative_bihistogram(upper, lower, opt), 1.0);
  const RenderedFigure r = renderer_->render(f, temp_dir("bihist") + "/bihist");
  const auto t = stats::CsvTable::read_file(r.csv);
  ASSERT_EQ(t.row_count(), 2u);
  const auto h1 = t.numeric_column("upper_height").values;
  const auto h2 = t.numeric_column("lower_height").values;
  // Width 1: heights 3/4, 1/4 above and 1/2, 1/2 below; each side has area 1.
  EXPECT_DOUBLE_EQ(h1[0], 0.75);
  EXPECT_DOUBLE_EQ(h1[1], 0.25);
  EXPECT_DOUBLE_EQ(h2[0], 0.5);
  EXPECT_DOUBLE_EQ(h2[1], 0.5);
  EXPECT_EQ(t.numeric_column("upper_count").values, (std::vector<double>{3, 1}));

  // In the picture: the first upper bar (colour 0) reaches 0.75 and the first lower bar
  // (colour 1) reaches -0.5, read at the bar's centre column.
  const RgbImage img = read_png(r.png);
  const FigureLayout& L = r.layout;
  auto column_of = [&](double x) {
    return int(L.plot_left + (x - L.x_min) / (L.x_max - L.x_min) * (L.plot_right - L.plot_left));
  };
  auto value_of_row = [&](double y) {
    return L.y_max - (y + 0.5 - L.plot_top) / (L.plot_bottom - L.plot_top) * (L.y_max - L.y_min);
  };
  unsigned char c0[3], c1[3];
  series_color(0, c0);
  series_color(1, c1);
  // Bars are filled with the colour at alpha 200 over white: compare with the blend.
  unsigned char b0[3], b1[3];
  for (int k = 0; k < 3; ++k) {
    b0[k] = (unsigned char)std::lround((c0[k] * 200 + 255 * 55) / 255.0);
    b1[k] = (unsigned char)std::lround((c1[k] * 200 + 255 * 55) / 255.0);
  }
  const int col = column_of(0.5);
  int top_upper = -1, bottom_lower = -1;
  for (int y = int(L.plot_top); y < int(L.plot_bottom); ++y) {
    if (top_upper < 0 && near_color(img.at(col, y), b0, 20)) top_upper = y;
    if (near_color(img.at(col, y), b1, 20)) bottom_lower = y;
  }
  ASSERT_GE(top_upper, 0);
  ASSERT_GE(bottom_lower, 0);
  const double px = (L.y_max - L.y_min) / (L.plot_bottom - L.plot_top);
  EXPECT_NEAR(value_of_row(top_upper), 0.75, 3 * px);
  EXPECT_NEAR(value_of_row(bottom_lower), -0.5, 3 * px);
}

// Why: the box plots' y range is restricted to the box bodies (paper Figs. 6, 8, 10, 12), and the
// figure must say so when a maximum lies outside it; widths are proportional to n.
TEST_F(RendererTest, BoxPlotRestrictsTheRangeAndSaysWhatIsOutside) {
  BoxPlotContent c;
  c.categories = {"A", "B"};
  c.series = {"platform I", "platform II"};
  c.boxes = {{"A", "platform I", 0, 1, 2, 3, 5, 0, 100, 400, 0, 3},
             {"A", "platform II", 0, 1, 2, 3, 5, 0, 4, 100, 0, 0},
             {"B", "platform I", 1, 2, 3, 4, 6, 1, 6, 400, 0, 0},
             {"B", "platform II", 1, 2, 3, 4, 6, -50, 6, 200, 1, 0}};
  Figure f;
  f.id = "box";
  f.title = "Box plot: LSEs-norm by view group and platform";
  f.x_label = "view group";
  f.y_label = "LSEs-norm (x 10^-3)";
  f.content = c;
  const RenderedFigure r = renderer_->render(f, temp_dir("box") + "/box");
  double lo, hi;
  box_plot_y_range(c, &lo, &hi);
  EXPECT_DOUBLE_EQ(r.layout.y_min, lo);
  EXPECT_DOUBLE_EQ(r.layout.y_max, hi);
  EXPECT_LT(hi, 100);  // the maximum of A / platform I is far outside
  EXPECT_NE(r.note.find("Above the plot: A platform I (max 100)"), std::string::npos) << r.note;
  EXPECT_NE(r.note.find("Below the plot: B platform II (min -50)"), std::string::npos) << r.note;
  const auto t = stats::CsvTable::read_file(r.csv);
  EXPECT_EQ(t.numeric_column("relative_width").values,
            (std::vector<double>{1.0, 0.25, 1.0, 0.5}));
  // The note is printed on the figure: it is in the PDF's text.
  const std::string text = shell_output("pdftotext -layout '" + r.pdf + "' -");
  EXPECT_NE(text.find("Above the plot"), std::string::npos) << text;
  EXPECT_NE(text.find("Box plot: LSEs-norm"), std::string::npos) << text;
}

// Why: the history's trend boxes (the IQR around the median, no whiskers) were captioned "no
// whiskers" by the trend and "beyond the whiskers" by the renderer. The note says what is drawn.
TEST_F(RendererTest, BoxPlotNoteNamesOnlyTheMarksItDraws) {
  BoxPlotContent c;
  c.categories = {"#1", "#2"};
  c.series = {"s"};
  // box, lower_whisker = q1 = min, upper_whisker = q3 = max: a band without whiskers
  c.boxes = {{"#1", "s", 1, 1, 2, 3, 3, 1, 3, 10, 0, 0}, {"#2", "s", 2, 2, 3, 4, 4, 2, 4, 10, 0, 0}};
  Figure f;
  f.id = "band";
  f.title = "Trend";
  f.x_label = "audit";
  f.y_label = "TEu (px^2)";
  f.content = c;
  const RenderedFigure r = renderer_->render(f, temp_dir("band") + "/band");
  EXPECT_EQ(r.note.find("whisker"), std::string::npos) << r.note;
  EXPECT_EQ(r.note.find("triangles"), std::string::npos) << r.note;
  EXPECT_NE(r.note.find("Box widths proportional to n."), std::string::npos) << r.note;
}

// Why: a history of many platforms x kinds x view groups has more series than the 8 colours of
// the palette; series 9 on took series 1's colour again. Every series gets its own colour.
TEST(SeriesColor, SixtyFourSeriesHaveSixtyFourDistinctColours) {
  std::vector<std::array<unsigned char, 3>> seen;
  for (std::size_t i = 0; i < 64; ++i) {
    std::array<unsigned char, 3> c{};
    series_color(i, c.data());
    for (std::size_t j = 0; j < seen.size(); ++j) {
      const int d = std::abs(c[0] - seen[j][0]) + std::abs(c[1] - seen[j][1]) +
                    std::abs(c[2] - seen[j][2]);
      EXPECT_GT(d, 6) << "series " << i << " and " << j;
    }
    seen.push_back(c);
  }
  unsigned char first[3];
  series_color(0, first);
  EXPECT_EQ(first[0], 0);  // the palette's first colour (Okabe-Ito blue) is kept
  EXPECT_EQ(first[1], 114);
  EXPECT_EQ(first[2], 178);
}

// Why: the speed-against-error figure is read by where its markers sit on log axes; each
// marker's centre pixel must be its series' colour at log10 of its values, the legend must name
// each series (platform), the ticks must be readable powers of ten, and a point with a zero value
// cannot sit on a log axis: it is left out and the note says so.
TEST_F(RendererTest, ScatterOnLogAxesPutsMarkersWhereTheValuesAreAndNamesTheOmitted) {
  ScatterContent c;
  c.x_log10 = c.y_log10 = true;
  c.series = {{"platform I", {2, 200}, {0.05, 5}, {"A", "C"}, {1.5, 150}, {3, 260}, {0.04, 4},
               {0.07, 6}},
              {"platform II", {20, 50}, {0.5, 0}, {"A", "C"}, {}, {}, {}, {}}};
  Figure f;
  f.id = "scatter";
  f.title = "Render time against error: test";
  f.x_label = "render time per primitive, median (us, log scale)";
  f.y_label = "PEnorm x 10^3, median, log scale";
  f.content = c;
  const RenderedFigure r = renderer_->render(f, temp_dir("scatter") + "/scatter");
  const FigureLayout& L = r.layout;
  ASSERT_TRUE(L.x_log10 && L.y_log10);
  // The range holds every drawable value and bar end (log10 units).
  EXPECT_LT(L.x_min, std::log10(1.5));
  EXPECT_GT(L.x_max, std::log10(260));
  EXPECT_LT(L.y_min, std::log10(0.04));
  EXPECT_GT(L.y_max, std::log10(6));
  const RgbImage img = read_png(r.png);
  const auto column = [&](double v) {
    return int(std::lround(L.plot_left + (std::log10(v) - L.x_min) / (L.x_max - L.x_min) *
                                             (L.plot_right - L.plot_left) - 0.5));
  };
  const auto row = [&](double v) {
    return int(std::lround(L.plot_top + (L.y_max - std::log10(v)) / (L.y_max - L.y_min) *
                                            (L.plot_bottom - L.plot_top) - 0.5));
  };
  // A marker's centre (radius 6 px) is its colour within a pixel or two of where it should be.
  const auto marker_at = [&](double x, double y, const unsigned char rgb[3]) {
    const int cx = column(x), cy = row(y);
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (!near_color(img.at(cx + dx, cy + dy), rgb, 12)) return false;
    return true;
  };
  unsigned char c0[3], c1[3];
  series_color(0, c0);
  series_color(1, c1);
  EXPECT_TRUE(marker_at(2, 0.05, c0));
  EXPECT_TRUE(marker_at(200, 5, c0));
  EXPECT_TRUE(marker_at(20, 0.5, c1));
  // ... and nowhere else: no marker colour at a place without a point (and the picture is not
  // one colour).
  EXPECT_FALSE(near_color(img.at(column(20), row(5)), c0, 12));
  EXPECT_FALSE(near_color(img.at(column(20), row(5)), c1, 12));
  std::size_t c1_pixels = 0;
  for (int y = int(L.plot_top) + 1; y < int(L.plot_bottom); ++y)
    for (int x = int(L.plot_left) + 1; x < int(L.plot_right); ++x)
      c1_pixels += near_color(img.at(x, y), c1, 12);
  EXPECT_GT(c1_pixels, 60u);   // one marker of radius 6: about 113 px
  EXPECT_LT(c1_pixels, 200u);  // not two: the zero-error point is not drawn
  // The note names it, on the figure too; the legend names both platforms; ticks read as numbers.
  EXPECT_NE(r.note.find("1 point not drawn"), std::string::npos) << r.note;
  EXPECT_NE(r.note.find("C platform II (y = 0)"), std::string::npos) << r.note;
  const std::string text = squeeze(shell_output("pdftotext -layout '" + r.pdf + "' -"));
  EXPECT_NE(text.find("1 point not drawn"), std::string::npos) << text;
  EXPECT_NE(text.find("platform I"), std::string::npos) << text;
  EXPECT_NE(text.find("platform II"), std::string::npos) << text;
  EXPECT_NE(text.find("100"), std::string::npos) << text;
  EXPECT_NE(text.find("0.1"), std::string::npos) << text;
  // The CSV keeps every point, the omitted one included.
  const auto t = stats::CsvTable::read_file(r.csv);
  EXPECT_EQ(t.row_count(), 4u);
  EXPECT_EQ(t.numeric_column("y").values, (std::vector<double>{0.05, 5, 0.5, 0}));
}

// A bar's colour where its fill (alpha 220 over the white background) shows.
std::array<unsigned char, 3> bar_fill(const unsigned char c[3]) {
  std::array<unsigned char, 3> out{};
  for (int i = 0; i < 3; ++i) out[i] = (unsigned char)std::lround(c[i] * 220.0 / 255 + 35.0);
  return out;
}

// Why: the visibility figures put 2 false-invisible cases in 10,000 on a 0-100 % axis: a bar of
// 0.01 px, seen only through its label. On the log axis it has a bar a reader sees.
TEST_F(RendererTest, LogBarsGiveARareClassAVisibleBar) {
  BarChartContent c;
  c.categories = {"true-visible", "false-visible", "false-invisible"};
  c.series = {{"A", {99.97, 0, 0.02}, {"9997", "0", "2"}, std::nullopt}};
  c.y_max = 100;
  c.y_log10 = true;
  Figure f;
  f.id = "bars_log";
  f.title = "Visibility classes: test, view group A";
  f.x_label = "visibility class";
  f.y_label = "share of the group's cases (%, log scale)";
  f.content = c;
  const RenderedFigure r = renderer_->render(f, temp_dir("bars_log") + "/bars_log");
  const FigureLayout& L = r.layout;
  ASSERT_TRUE(L.y_log10);
  EXPECT_NEAR(L.y_min, std::log10(bar_chart_log_floor(c)), 1e-9);
  EXPECT_NEAR(bar_chart_log_floor(c), 0.001, 1e-12);  // a decade below 0.02
  const auto row = [&](double v) {
    return L.plot_top + (L.y_max - std::log10(v)) / (L.y_max - L.y_min) * (L.plot_bottom - L.plot_top);
  };
  const auto column = [&](double x) {
    return int(std::lround(L.plot_left + (x - L.x_min) / (L.x_max - L.x_min) *
                                             (L.plot_right - L.plot_left)));
  };
  const double height = L.plot_bottom - row(0.02);
  EXPECT_GE(height, 40) << "2 in 10,000 on a 0-100 axis of this size would be "
                        << 0.02 / 100 * (L.plot_bottom - L.plot_top) << " px";
  // ... and drawn: the bar's fill just above the axis and just below its top
  unsigned char c0[3];
  series_color(0, c0);
  const auto fill = bar_fill(c0);
  const RgbImage img = read_png(r.png);
  const int x = column(3);
  EXPECT_TRUE(near_color(img.at(x, int(L.plot_bottom) - 4), fill.data(), 12));
  EXPECT_TRUE(near_color(img.at(x, int(row(0.02)) + 4), fill.data(), 12));
  EXPECT_FALSE(near_color(img.at(x, int(row(0.02)) - 6), fill.data(), 12));
  // a count of 0 has no bar, only its label
  EXPECT_FALSE(near_color(img.at(column(2), int(L.plot_bottom) - 4), fill.data(), 12));
}

// Why: the conformance classes took the palette's colours by position: violation came out teal.
TEST_F(RendererTest, TheViolationBarIsRed) {
  an::ConformanceCounts n;
  n.exact = 80, n.snapped = 10, n.within_spec = 5, n.violation = 5;
  Figure f;
  f.id = "classes";
  f.title = "GL conformance classes other than exact, test, view group A";
  f.x_label = "view group";
  f.y_label = "share of records (%)";
  f.content = conformance_class_bars({{"A", n}});
  const RenderedFigure r = renderer_->render(f, temp_dir("classes") + "/classes");
  const FigureLayout& L = r.layout;
  const RgbImage img = read_png(r.png);
  const Rgb red = conformance_class_color(metrics::Conformance::kViolation);
  const unsigned char rgb[3] = {red[0], red[1], red[2]};
  const double slot = 0.8 / 3;  // three series: violation is the third bar of the group
  const int x = int(std::lround(L.plot_left + (1 + slot - L.x_min) / (L.x_max - L.x_min) *
                                                  (L.plot_right - L.plot_left)));
  EXPECT_TRUE(near_color(img.at(x, int(L.plot_bottom) - 4), bar_fill(rgb).data(), 12));
}

// Rows and columns of a figure's plot where values lie (linear axes), and dark ink.
struct PlotPixels {
  const FigureLayout& L;
  const RgbImage& img;
  int column(double x) const {
    return int(std::lround(
        L.plot_left + (x - L.x_min) / (L.x_max - L.x_min) * (L.plot_right - L.plot_left) - 0.5));
  }
  int row(double y) const {
    return int(std::lround(
        L.plot_top + (L.y_max - y) / (L.y_max - L.y_min) * (L.plot_bottom - L.plot_top) - 0.5));
  }
  bool dark(int x, int y) const {
    const unsigned char* p = img.at(x, y);
    return p[0] + p[1] + p[2] < 600;  // text and tick marks, their anti-aliased edges too
  }
};

// Why: the first page's figure drew a tick mark between the letters of every category ("P|A"),
// and each y tick ended 1 px from its label ("35-"). A category has no tick mark; a tick ends
// with background between it and its label.
TEST_F(RendererTest, NoTickMarkReachesALabel) {
  BarChartContent c;
  c.categories = {"P A", "P B", "L A", "T D"};
  c.series = {{"p", {0.5, 3.25, 14.7, 38.0}, {"0.50", "3.25", "14.70", "38.00"}, std::nullopt}};
  Figure f;
  f.id = "ticks_bars";
  f.title = "Pixel sets that differ: test";
  f.x_label = "kind and view group";
  f.y_label = "differs (%)";
  f.content = c;
  const RenderedFigure r = renderer_->render(f, temp_dir("ticks_bars") + "/ticks_bars");
  const FigureLayout& L = r.layout;
  const RgbImage img = read_png(r.png);
  const PlotPixels px{L, img};
  EXPECT_FALSE(L.x_ticks_visible);
  ASSERT_EQ(L.x_tick_labels, c.categories);
  // under each category, down to where its label begins: nothing (the middle of "P A" is the
  // space between its letters)
  const int axis = int(L.plot_bottom);
  for (std::size_t i = 0; i < L.x_ticks.size(); ++i)
    for (int y = axis + 2; y <= axis + 8; ++y)
      EXPECT_FALSE(px.dark(px.column(L.x_ticks[i]), y)) << c.categories[i] << ", row " << y;
  // each y tick: its mark left of the axis, background, then its label
  ASSERT_GE(L.y_ticks.size(), 3u);
  const int left = int(L.plot_left);
  for (std::size_t i = 0; i < L.y_ticks.size(); ++i) {
    const int y = px.row(L.y_ticks[i]);
    EXPECT_TRUE(px.dark(left - 3, y) || px.dark(left - 3, y - 1) || px.dark(left - 3, y + 1))
        << "no tick mark at " << L.y_tick_labels[i];
    int ink = 0;
    for (int dy = -10; dy <= 10; ++dy)
      for (int x = left - 9; x <= left - 7; ++x) ink += px.dark(x, y + dy);
    EXPECT_EQ(ink, 0) << "tick " << L.y_tick_labels[i] << " reaches its label";
  }
}

// Decimals of a tick label ("0.10": 2, "100": 0).
int decimals(const std::string& label) {
  const auto dot = label.find('.');
  return dot == std::string::npos ? 0 : int(label.size() - dot - 1);
}

// Why: VTK's own ticks labelled a histogram's axis 0.08, 0.1, 0.12: one scale written three ways.
// Every tick of a linear axis has the decimals of the axis' step; its mark stops short of its
// label.
TEST_F(RendererTest, AnAxisWritesEveryTickWithTheSameDecimals) {
  NamedSample a{"A: 30 deg, 128x128", {}};
  for (int i = 0; i < 2000; ++i) a.values.push_back(0.28 * std::pow((i + 0.5) / 2000, 3));
  const Figure f =
      histogram_figure("ticks_hist", "Histogram of LSEs: test, view group A", "LSEs (px)", {a});
  const RenderedFigure r = renderer_->render(f, temp_dir("ticks_hist") + "/ticks_hist");
  const FigureLayout& L = r.layout;
  EXPECT_TRUE(L.x_ticks_visible);
  for (const auto* labels : {&L.x_tick_labels, &L.y_tick_labels}) {
    ASSERT_GE(labels->size(), 4u);
    for (const std::string& l : *labels)
      EXPECT_EQ(decimals(l), decimals(labels->front())) << l << " beside " << labels->front();
  }
  EXPECT_NE(std::find(L.x_tick_labels.begin(), L.x_tick_labels.end(), "0.10"),
            L.x_tick_labels.end());
  // the labels are the positions, in the axis' decimals
  for (std::size_t i = 0; i < L.x_ticks.size(); ++i)
    EXPECT_NEAR(std::stod(L.x_tick_labels[i]), L.x_ticks[i], 1e-12) << L.x_tick_labels[i];
  // x tick marks end above the labels: background between, across the plot's width
  const RgbImage img = read_png(r.png);
  const PlotPixels px{L, img};
  const int axis = int(L.plot_bottom);
  EXPECT_TRUE(px.dark(px.column(L.x_ticks[1]), axis + 3)) << "no tick mark";
  int ink = 0;
  for (int x = int(L.plot_left); x < int(L.plot_right); ++x)
    for (int y = axis + 6; y <= axis + 8; ++y) ink += px.dark(x, y);
  EXPECT_EQ(ink, 0) << "a tick mark reaches down to its label";
}

// Why: a narrow view group on a wide one's axis fell into 3 bins, and one group's outline hid
// another's: each gets a panel of its own, stacked, on its own axis.
TEST_F(RendererTest, HistogramPanelsStackOneAxisPerGroup) {
  NamedSample a{"A: 30 deg, 128x128", {}}, b{"B: 30 deg, 907x907", {}};
  for (int i = 0; i < 1000; ++i)
    a.values.push_back(std::sin(i * 0.7) + 1), b.values.push_back(0.01 * std::cos(i * 1.3));
  const Figure f = histogram_figure("panels", "Histogram: test, view groups A, B", "x", {a, b});
  const RenderedFigure r = renderer_->render(f, temp_dir("panels") + "/panels");
  ASSERT_EQ(r.panels.size(), 2u);
  EXPECT_LT(r.panels[0].plot_bottom, r.panels[1].plot_top) << "the first panel is above";
  EXPECT_GT(r.panels[0].x_max - r.panels[0].x_min, 50 * (r.panels[1].x_max - r.panels[1].x_min));
  EXPECT_GT(r.panels[1].plot_bottom - r.panels[1].plot_top, 80);
  const std::string text = squeeze(shell_output("pdftotext -layout '" + r.pdf + "' -"));
  EXPECT_NE(text.find("A: 30 deg, 128x128 (n = 1000)"), std::string::npos) << text;
  EXPECT_NE(text.find("B: 30 deg, 907x907 (n = 1000)"), std::string::npos) << text;
}

}  // namespace
}  // namespace ra::plots
