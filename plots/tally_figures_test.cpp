// The conformance figures: each class has one colour in every figure, whichever classes a figure
// holds, and violation is the red one; a share keeps its hue across platforms; the numbers of a
// figure share one format; titles name one view group in the singular and a box plot for what it
// shows.
#include "plots/figure_planner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace ra::plots {
namespace {

using metrics::Conformance;

// Why: the figures showed "violation" in the palette's third colour (teal) and "within-spec" in
// amber: a colour by position reads backwards, and would change with the classes present.
TEST(ConformanceClassBars, EachClassHasItsOwnColourWhicheverClassesAreThere) {
  an::ConformanceCounts only_violations;
  only_violations.exact = 90, only_violations.violation = 10;
  an::ConformanceCounts no_violation;
  no_violation.exact = 50, no_violation.snapped = 30, no_violation.within_spec = 20;
  const BarChartContent one = conformance_class_bars({{"A", only_violations}});
  const BarChartContent two = conformance_class_bars({{"A", no_violation}, {"B", only_violations}});
  const std::map<std::string, Conformance> named = {{"snapped", Conformance::kSnapped},
                                                    {"within-spec", Conformance::kWithinSpec},
                                                    {"violation", Conformance::kViolation}};
  for (const BarChartContent* c : {&one, &two}) {
    ASSERT_EQ(c->series.size(), 3u);
    for (const BarSeries& s : c->series) {
      ASSERT_TRUE(named.count(s.name)) << s.name << ": not a class of docs/conformance.md";
      ASSERT_TRUE(s.color.has_value()) << s.name;
      EXPECT_EQ(*s.color, conformance_class_color(named.at(s.name))) << s.name;
    }
  }
  EXPECT_EQ(one.categories, (std::vector<std::string>{"A (exact 90.0%)"}));
  EXPECT_EQ(one.series[2].labels, (std::vector<std::string>{"10.0"}));

  // violation is the red one; the others are calm (blue above red), darker the better the class
  const Rgb red = conformance_class_color(Conformance::kViolation);
  EXPECT_GE(red[0], 180);
  EXPECT_LE(red[1], 60);
  EXPECT_LE(red[2], 60);
  const auto luminance = [](Rgb c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; };
  double last = -1;
  for (Conformance k : {Conformance::kExact, Conformance::kSnapped, Conformance::kWithinSpec}) {
    const Rgb c = conformance_class_color(k);
    EXPECT_GT(c[2], c[0]) << metrics::conformance_name(k) << " looks alarming";
    EXPECT_GT(luminance(c), last) << metrics::conformance_name(k);
    last = luminance(c);
    EXPECT_NE(c, red);
  }
}

// HSV hue of a colour, degrees in [0, 360); NaN for a grey.
double hue(Rgb c) {
  const double r = c[0] / 255.0, g = c[1] / 255.0, b = c[2] / 255.0;
  const double hi = std::max({r, g, b}), lo = std::min({r, g, b}), d = hi - lo;
  if (d == 0) return NAN;
  double h = hi == r ? std::fmod((g - b) / d, 6.0) : hi == g ? (b - r) / d + 2 : (r - g) / d + 4;
  h *= 60;
  return h < 0 ? h + 360 : h;
}
double hue_distance(double a, double b) {
  const double d = std::fabs(a - b);
  return std::min(d, 360 - d);
}

// Decimals of a label ("38.00": 2, "0": 0, "<0.01": 2).
int decimals(const std::string& label) {
  const auto dot = label.find('.');
  return dot == std::string::npos ? 0 : int(label.size() - dot - 1);
}

an::ReferenceAgreement agreement(std::uint64_t compared, std::uint64_t identical,
                                 std::uint64_t drawn, std::uint64_t drawn_identical) {
  an::ReferenceAgreement a;
  a.compared = compared, a.identical = identical, a.drawn = drawn;
  a.drawn_identical = drawn_identical;
  return a;
}

// Why: conformance.line of two platforms drew llvmpipe's two shares blue and orange and
// softpipe's green and pink: a reader needed the legend to pair softpipe's "all cases" with
// llvmpipe's. A share is one hue, each platform a shade of it.
TEST(ConformanceBars, AShareKeepsItsHueAcrossPlatformsEachPlatformItsShade) {
  const an::ReferenceAgreement l_a = agreement(1000, 993, 100, 93),
                               l_b = agreement(1000, 978, 500, 478);
  const an::ReferenceAgreement s_a = agreement(1000, 901, 100, 1),
                               s_b = agreement(1000, 407, 500, 14);
  const BarChartContent c = conformance_bars(
      {"A: 30 deg, 128x128", "B: 150 deg, 128x128"},
      {{"llvmpipe", {&l_a, &l_b}}, {"softpipe", {&s_a, &s_b}}, {"reference", {nullptr, nullptr}}});
  // the platform without comparisons has no bars; the bars go share by share
  ASSERT_EQ(c.series.size(), 4u);
  EXPECT_EQ(c.series[0].name, "llvmpipe, all cases");
  EXPECT_EQ(c.series[1].name, "softpipe, all cases");
  EXPECT_EQ(c.series[2].name, "llvmpipe, cases with lit pixels");
  EXPECT_EQ(c.series[3].name, "softpipe, cases with lit pixels");
  for (const BarSeries& s : c.series) ASSERT_TRUE(s.color.has_value()) << s.name;
  const Rgb all_l = *c.series[0].color, all_s = *c.series[1].color;
  const Rgb lit_l = *c.series[2].color, lit_s = *c.series[3].color;
  // one hue per share (rounding to 8 bits moves it by a degree or so) ...
  EXPECT_LT(hue_distance(hue(all_l), hue(all_s)), 2.0);
  EXPECT_LT(hue_distance(hue(lit_l), hue(lit_s)), 2.0);
  // ... far from the other share's
  EXPECT_GT(hue_distance(hue(all_l), hue(lit_l)), 90.0);
  // the first platform in the share's own colour, the second lighter
  EXPECT_EQ(all_l, differs_share_color(false));
  EXPECT_EQ(lit_l, differs_share_color(true));
  const auto luminance = [](Rgb x) { return 0.2126 * x[0] + 0.7152 * x[1] + 0.0722 * x[2]; };
  EXPECT_GT(luminance(all_s), luminance(all_l) + 40);
  EXPECT_GT(luminance(lit_s), luminance(lit_l) + 40);

  // the shares, and one format for every label of the figure: 0.70 beside 59.30, not 59.3
  EXPECT_NEAR(c.series[1].values[1], 59.3, 1e-9);
  EXPECT_EQ(c.series[0].labels, (std::vector<std::string>{"0.70", "2.20"}));
  EXPECT_EQ(c.series[1].labels, (std::vector<std::string>{"9.90", "59.30"}));
  EXPECT_EQ(c.series[2].labels, (std::vector<std::string>{"7.00", "4.40"}));
  EXPECT_EQ(c.series[3].labels, (std::vector<std::string>{"99.00", "97.20"}));
}

// Why: the first page's figure labelled its bars 10.00, 38.0 and 14.7: three formats in one
// figure. One number of decimals for every label, whatever the share's size.
TEST(ConformanceBars, EveryLabelOfAFigureHasTheSameDecimals) {
  const an::ReferenceAgreement a = agreement(10000, 9998, 10000, 9998);  // 0.02 %
  const an::ReferenceAgreement b = agreement(1000, 620, 1000, 620);      // 38 %
  const an::ReferenceAgreement d = agreement(3000, 2559, 3000, 2559);    // 14.7 %
  const an::ReferenceAgreement e = agreement(100000, 99999, 100000, 1);  // 99.999 % of the lit
  const an::ReferenceAgreement none = agreement(10, 10, 0, 0);           // nothing lit
  const BarChartContent c =
      conformance_bars({"A", "B", "C", "D", "E"}, {{"p", {&a, &b, &d, &e, &none}}});
  ASSERT_EQ(c.series.size(), 2u);
  EXPECT_EQ(c.series[0].labels, (std::vector<std::string>{"0.02", "38.00", "14.70", "<0.01", "0"}));
  // 99.999 % is not all of them: it does not read as 100
  EXPECT_EQ(c.series[1].labels,
            (std::vector<std::string>{"0.02", "38.00", "14.70", ">99.99", "n/a"}));
  for (const BarSeries& s : c.series)
    for (const std::string& l : s.labels)
      if (l != "0" && l != "n/a") {
        EXPECT_EQ(decimals(l), 2) << l;
      }

  // all shares of 10 % or more: one decimal each
  EXPECT_EQ(percent_decimals({38.0, 14.7, 0, 100}), 1);
  EXPECT_EQ(percent_decimals({38.0, 9.99}), 2);
  EXPECT_EQ(percent_text(38.0, 1), "38.0");
  EXPECT_EQ(percent_text(100.0, 2), "100.00");
}

// Why: a figure of one box was titled "Box plots of TEu by platform": it shows one platform's box
// of one view group, and says so.
TEST(BoxPlotTitle, NamesWhatVariesAndASingleBoxInTheSingular) {
  BoxPlotContent one;
  one.categories = {"B: 150 deg, 128x128"};
  one.series = {"osmesa-llvmpipe"};
  one.boxes = {{"B: 150 deg, 128x128", "osmesa-llvmpipe", 9, 26, 33, 38, 56, 0.5, 80, 200, 3, 2}};
  EXPECT_EQ(box_plot_title("TEu", one), "Box plot of TEu");

  BoxPlotContent groups = one;
  groups.categories.push_back("D: 150 deg, 907x907");
  groups.boxes.push_back(one.boxes[0]);
  groups.boxes[1].category = "D: 150 deg, 907x907";
  EXPECT_EQ(box_plot_title("TEu", groups), "Box plots of TEu by view group");

  BoxPlotContent platforms = one;
  platforms.series.push_back("osmesa-softpipe");
  platforms.boxes.push_back(one.boxes[0]);
  platforms.boxes[1].series = "osmesa-softpipe";
  EXPECT_EQ(box_plot_title("TEu", platforms), "Box plots of TEu by platform");

  BoxPlotContent both = groups;
  both.series.push_back("osmesa-softpipe");
  both.boxes.push_back(platforms.boxes[1]);
  EXPECT_EQ(box_plot_title("TEu", both), "Box plots of TEu by view group and platform");
}

TEST(GroupsPhrase, NamesOneViewGroupInTheSingular) {
  EXPECT_EQ(groups_phrase({"A"}), "view group A");
  EXPECT_EQ(groups_phrase({"A", "B", "C", "D"}), "view groups A-D");
  EXPECT_EQ(groups_phrase({"A", "C"}), "view groups A, C");
}

}  // namespace
}  // namespace ra::plots
