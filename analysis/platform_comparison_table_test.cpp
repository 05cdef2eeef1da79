// The cross-platform comparison (platform_comparison_table.cpp): which pairs of platforms, metrics
// and view groups are compared, the medians, IQRs and differences against values computed by hand,
// the "differs" flags on samples built to differ (or not) in location and spread, a group one
// platform has no values in, constant samples, and a run with one platform.
#include "analysis/paper_tables.h"

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "analysis/records_testing.h"

namespace ra::analysis {
namespace {

using metrics::Visibility;
using testing::point;
using testing::write_records;

// Points, group A (views 1 and 2):
//   p1: 0.1 0.2 0.3 | 0.4 0.5     HF6 median 0.3, Q1 at 1.5 = 0.15, Q3 at 4.5 = 0.45, IQR 0.3
//   p2: 0.2 0.4 0.6 | 0.8 1.0     (p1 doubled) median 0.6, Q1 0.3, Q3 0.9, IQR 0.6
//   p3: 5.1 5.2 5.3 | 5.4 5.5     (p1 + 5) median 5.3, IQR 0.3
// Group B (view 3): p1 has true-invisible points only (the group exists, without values); p3 has
// 0.25 and 0.75; p2 has no record there.
std::vector<metrics::Record> three_platforms() {
  std::vector<metrics::Record> rs;
  const std::vector<double> base = {0.1, 0.2, 0.3, 0.4, 0.5};
  for (const auto& [platform, scale, shift] :
       {std::tuple{"p1", 1.0, 0.0}, std::tuple{"p2", 2.0, 0.0}, std::tuple{"p3", 1.0, 5.0}}) {
    for (std::uint64_t i = 0; i < base.size(); ++i)
      rs.push_back(point(platform, i < 3 ? 1 : 2, i, base[i] * scale + shift));
  }
  rs.push_back(point("p1", 3, 10, 0, Visibility::kTrueInvisible));
  rs.push_back(point("p1", 3, 11, 0, Visibility::kTrueInvisible));
  rs.push_back(point("p3", 3, 10, 0.25));
  rs.push_back(point("p3", 3, 11, 0.75));
  return rs;
}

std::vector<std::string> texts(const std::vector<stats::TableCell>& row) {
  std::vector<std::string> out;
  for (const stats::TableCell& c : row) out.push_back(c.text);
  return out;
}

class PlatformComparisonTable : public ::testing::Test {
 protected:
  void SetUp() override {
    write_records(dir_.path, three_platforms());
    run_ = load_run_records(dir_.path.string());
    options_.jobs = 1;
    summaries_.emplace(run_, options_.quantiles, 1);
    rows_ = compare_platforms(run_, *summaries_, options_);
  }
  testing::ScopedTempDir dir_{"platform_comparison"};
  RunRecords run_;
  TableOptions options_;
  std::optional<GroupSummaries> summaries_;
  std::vector<PlatformComparison> rows_;
};

// Every pair a < b of platforms that both have the view group, for each metric of the kind: group
// A gives (p1, p2), (p1, p3), (p2, p3); group B only (p1, p3); PE and PEnorm each.
TEST_F(PlatformComparisonTable, EveryPairIsComparedWhereBothPlatformsHaveTheGroup) {
  ASSERT_EQ(rows_.size(), 8u);
  const std::vector<std::tuple<std::size_t, std::string, std::size_t, std::size_t>> want = {
      {0, "A", 0, 1}, {0, "A", 0, 2}, {0, "A", 1, 2}, {0, "B", 0, 2},
      {1, "A", 0, 1}, {1, "A", 0, 2}, {1, "A", 1, 2}, {1, "B", 0, 2}};
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    EXPECT_EQ(rows_[i].kind, geometry::Kind::kPoint);
    EXPECT_EQ(std::tuple(rows_[i].metric, rows_[i].label, rows_[i].platform_a, rows_[i].platform_b),
              want[i])
        << i;
  }
  ASSERT_TRUE(rows_[0].a && rows_[0].b);
  EXPECT_EQ(rows_[0].a->n, 5u);
  EXPECT_NEAR(rows_[0].a->median, 0.3, 1e-15);
  EXPECT_NEAR(rows_[0].b->median, 0.6, 1e-15);
  EXPECT_NEAR(rows_[0].a->iqr, 0.3, 1e-15);
  EXPECT_NEAR(rows_[0].b->iqr, 0.6, 1e-15);
  EXPECT_NEAR(rows_[1].b->median, 5.3, 1e-14);
}

// The table's numbers: n, medians, IQRs and the differences a - b, in metric units (PE, px).
TEST_F(PlatformComparisonTable, MediansIqrsAndTheirDifferencesAreHandComputed) {
  const stats::Table t = cross_platform_table(run_, rows_, options_);
  EXPECT_EQ(t.file_stem, "cross_platform");
  EXPECT_NE(t.title.find("alpha = 0.05"), std::string::npos);
  ASSERT_EQ(t.columns.size(), 25u);
  ASSERT_EQ(t.rows.size(), 8u);
  const std::vector<std::string> r0 = texts(t.rows[0]);
  EXPECT_EQ(std::vector<std::string>(r0.begin(), r0.begin() + 14),
            (std::vector<std::string>{"point", "PE", "px", "A", "p1", "p2", "5", "5", "0.3", "0.6",
                                      "-0.3", "0.3", "0.6", "-0.3"}));
  const std::vector<std::string> r1 = texts(t.rows[1]);
  // (the IQRs' difference is rounding noise around 0, not compared)
  EXPECT_EQ(std::vector<std::string>(r1.begin() + 4, r1.begin() + 13),
            (std::vector<std::string>{"p1", "p3", "5", "5", "0.3", "5.3", "-5", "0.3", "0.3"}));
  // PEnorm = PE / 128, the median of each the normalised middle value (5 significant digits)
  const std::vector<std::string> r4 = texts(t.rows[4]);
  EXPECT_EQ(std::vector<std::string>(r4.begin(), r4.begin() + 10),
            (std::vector<std::string>{"point", "PEnorm", "sqrt(W*H) units", "A", "p1", "p2", "5",
                                      "5", stats::format_significant(0.3 / 128, 5), "0.0046875"}));
}

// p3 is p1 shifted by 5: the location test says they differ, Levene's test on the same spread
// says they do not. p2 (p1 doubled, n = 5 each) is not far enough from p1 for either at 0.05
// (Welch t = -0.3 / sqrt(0.025/5 + 0.1/5) = -1.90, p = 0.11).
TEST_F(PlatformComparisonTable, TheFlagsSayWhetherLocationAndSpreadDiffer) {
  const stats::Table t = cross_platform_table(run_, rows_, options_);
  ASSERT_EQ(t.columns[23].name, "Location");
  ASSERT_EQ(t.columns[24].name, "Spread");
  EXPECT_EQ(t.rows[1][23].text, "differs");
  EXPECT_EQ(t.rows[1][24].text, "same");
  EXPECT_EQ(t.rows[0][23].text, "same");
  EXPECT_EQ(t.rows[0][24].text, "same");
  ASSERT_TRUE(rows_[0].comparison.raw.welch.defined);
  EXPECT_NEAR(rows_[0].comparison.raw.welch.p_value, 0.11, 0.01);
  EXPECT_LT(rows_[1].comparison.raw.welch.p_value, 1e-6);
  EXPECT_GT(rows_[1].comparison.raw.levene_median.p_value, 0.99);
}

// Group B: p1's points there are all true-invisible. The pair is listed (both platforms have the
// group) with p1's n = 0 and "no data" in every other cell, never NaN.
TEST_F(PlatformComparisonTable, AGroupWithoutValuesOnOnePlatformSaysNoData) {
  EXPECT_FALSE(rows_[3].a.has_value());
  ASSERT_TRUE(rows_[3].b.has_value());
  EXPECT_EQ(rows_[3].b->n, 2u);
  const stats::Table t = cross_platform_table(run_, rows_, options_);
  const std::vector<std::string> r3 = texts(t.rows[3]);
  ASSERT_EQ(r3.size(), 25u);
  EXPECT_EQ(std::vector<std::string>(r3.begin(), r3.begin() + 8),
            (std::vector<std::string>{"point", "PE", "px", "B", "p1", "p3", "0", "2"}));
  for (std::size_t i = 8; i < r3.size(); ++i) EXPECT_EQ(r3[i], "no data") << t.columns[i].name;
}

// One platform: nothing to compare, and the table has its columns but no rows. Two constant
// samples: no test is defined, and the flags say so.
TEST(PlatformComparisonEdges, OnePlatformComparesNothingAndConstantSamplesAreUndefined) {
  testing::ScopedTempDir one{"platform_comparison_one"};
  write_records(one.path, {point("p1", 1, 0, 0.2), point("p1", 1, 1, 0.4)});
  const RunRecords single = load_run_records(one.path.string());
  TableOptions o;
  const GroupSummaries s1(single, o.quantiles, 1);
  EXPECT_TRUE(compare_platforms(single, s1, o).empty());
  const stats::Table empty = cross_platform_table(single, {}, o);
  EXPECT_TRUE(empty.rows.empty());
  EXPECT_EQ(empty.columns.size(), 25u);

  testing::ScopedTempDir constant{"platform_comparison_constant"};
  std::vector<metrics::Record> rs;
  for (std::uint64_t i = 0; i < 4; ++i) {
    rs.push_back(point("p1", 1, i, 0.25));
    rs.push_back(point("p2", 1, i, 0.25));
  }
  write_records(constant.path, rs);
  const RunRecords run = load_run_records(constant.path.string());
  const GroupSummaries s2(run, o.quantiles, 1);
  const std::vector<PlatformComparison> rows = compare_platforms(run, s2, o);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_FALSE(rows[0].comparison.raw.welch.defined);
  const stats::Table t = cross_platform_table(run, rows, o);
  EXPECT_EQ(t.rows[0][10].text, "0");  // median a - b
  EXPECT_EQ(t.rows[0][23].text, "undefined");
  EXPECT_EQ(t.rows[0][24].text, "undefined");
}

}  // namespace
}  // namespace ra::analysis
