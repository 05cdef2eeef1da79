// The conformance classes figure: each class has one colour in every figure, whichever classes a
// figure holds, and violation is the red one; titles name one view group in the singular and a
// box plot for what it shows.
#include "plots/figure_planner.h"

#include <gtest/gtest.h>

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
