// Tests of the paper's tables from a tiny synthetic run: hand-computed Hyndman-Fan 6 and 7 medians
// and IQRs of pooled view groups, visibility counts, "no data" instead of NaN, Table 11's
// conversion, the cross-platform comparison.
#include "analysis/paper_tables.h"

#include <gtest/gtest.h>

#include <algorithm>

#include <regex>

#include "analysis/records_testing.h"

namespace ra::analysis {
namespace {

using stats::QuantileDefinition;
using testing::point;
using testing::write_records;

// Platform p1: group A = view 1 {0.30, 0.10, 0.45, 0.20} + view 2 {0.25, 0.60, 0.05, 0.50, 0.40}
// (pooled, sorted: 0.05 0.10 0.20 0.25 0.30 0.40 0.45 0.50 0.60; HF6: median x(5) = 0.30,
// Q1 at 2.5: 0.15, Q3 at 7.5: 0.475, IQR 0.325; HF7: median 0.30, Q1 x(3) = 0.20, Q3 x(7) = 0.45,
// IQR 0.25). Group B (views 3, 4): nothing true-visible. Group C (views 5, 6): constant 0.2.
// Visibility extras in view 1; platform p2: group A only, {0.2, 0.4}.
std::vector<metrics::Record> tiny_run() {
  std::vector<metrics::Record> rs;
  std::uint64_t i = 0;
  for (double x : {0.30, 0.10, 0.45, 0.20}) rs.push_back(point("p1", 1, i++, x));
  for (double x : {0.25, 0.60, 0.05, 0.50, 0.40}) rs.push_back(point("p1", 2, i++, x));
  rs.push_back(point("p1", 1, i++, 0, metrics::Visibility::kTrueInvisible));
  rs.push_back(point("p1", 1, i++, 0, metrics::Visibility::kTrueInvisible));
  rs.push_back(point("p1", 1, i++, 0, metrics::Visibility::kFalseVisible));
  rs.push_back(point("p1", 1, i++, 0, metrics::Visibility::kFalseInvisible));
  rs.push_back(point("p1", 2, i++, 0, metrics::Visibility::kMultipleVisible));
  rs.push_back(
      point("p1", 2, i++, 0.1, metrics::Visibility::kTrueVisible, metrics::CaseStatus::kTimeout));
  rs.push_back(point("p1", 3, i++, 0, metrics::Visibility::kTrueInvisible));
  rs.push_back(point("p1", 4, i++, 0, metrics::Visibility::kTrueInvisible));
  for (int k = 0; k < 3; ++k) rs.push_back(point("p1", 5, i++, 0.2));
  for (int k = 0; k < 2; ++k) rs.push_back(point("p1", 6, i++, 0.2));
  rs.push_back(point("p2", 1, 0, 0.2));
  rs.push_back(point("p2", 2, 0, 0.4));
  return rs;
}

const stats::Table& find_table(const std::vector<stats::Table>& tables, const std::string& stem) {
  for (const stats::Table& t : tables) {
    if (t.file_stem == stem) return t;
  }
  throw std::runtime_error("no table " + stem);
}

std::vector<std::string> texts(const std::vector<stats::TableCell>& row) {
  std::vector<std::string> out;
  for (const stats::TableCell& c : row) out.push_back(c.text);
  return out;
}

class PaperTables : public ::testing::Test {
 protected:
  void SetUp() override {
    write_records(dir_.path, tiny_run());
    run_ = load_run_records(dir_.path.string());
  }
  testing::ScopedTempDir dir_{"paper_tables"};
  RunRecords run_;
};

TEST_F(PaperTables, MedianAndIqrAreHandComputedHf6) {
  TableOptions o;
  const auto tables = paper_tables(run_, o);
  const stats::Table& t3 = find_table(tables, "table03_pe");
  EXPECT_NE(t3.title.find("Table 3 (mirrors the paper's Table 3)"), std::string::npos);
  EXPECT_NE(t3.title.find("Hyndman-Fan 6"), std::string::npos);
  ASSERT_EQ(t3.rows.size(), 3u);  // groups A, B, C
  EXPECT_EQ(texts(t3.rows[0]), (std::vector<std::string>{"A", "30", "128", "0.30000", "0.32500",
                                                         "0.30000", "0.20000"}));
  EXPECT_EQ(texts(t3.rows[1]), (std::vector<std::string>{"B", "150", "128", "no data", "no data",
                                                         "no data", "no data"}));
  EXPECT_EQ(texts(t3.rows[2]), (std::vector<std::string>{"C", "30", "907", "0.20000", "0.00000",
                                                         "no data", "no data"}));
  // p2's group A {0.2, 0.4}: HF6 median 0.3, quartiles at 0.75 and 2.25 -> 0.2 and 0.4
  // Table 4: PEnorm x10^3 = PE / 128 x 1000
  const stats::Table& t4 = find_table(tables, "table04_pe_norm");
  EXPECT_EQ(t4.rows[0][3].text, "2.344");  // 0.30 / 128 = 2.34375e-3
  EXPECT_EQ(t4.rows[0][4].text, "2.539");  // 0.325 / 128 = 2.5390625e-3
  EXPECT_EQ(t4.rows[0][4].csv, "2.5390625");
  EXPECT_EQ(t4.rows[2][3].text, "0.221");  // 0.2 / 907
  EXPECT_EQ(t4.groups[1].label, "p1");
  EXPECT_EQ(t4.groups[2].label, "p2");
}

TEST_F(PaperTables, UncertaintyTableHasTheBootstrapErrorOfEveryCell) {
  TableOptions o;  // on by default: 2,000 resamples, seed 2008
  const auto tables = paper_tables(run_, o);
  const stats::Table& u = find_table(tables, "uncertainty");
  std::vector<std::vector<std::string>> table3;
  for (const auto& row : u.rows)
    if (row[0].text == "3") table3.push_back(texts(row));
  ASSERT_EQ(table3.size(), 3u);  // p1 A, p2 A, p1 C (B has no data)
  EXPECT_EQ(table3[0][2] + table3[0][3] + table3[0][4] + table3[0][5], "Ap190.300000");
  EXPECT_GT(std::stod(table3[0][6]), 0.0);
  // p1's group C is constant 0.2: every resample says so
  EXPECT_EQ(std::vector<std::string>(table3[2].begin() + 2, table3[2].end()),
            (std::vector<std::string>{"C", "p1", "5", "0.200000", "0.000000", "0.200000",
                                      "0.200000", "0.000000", "0.000000", "0.000000",
                                      "0.000000"}));
  // p2's group A {0.2, 0.4}: a resample's HF6 median is the mean of two draws, 0.2 / 0.3 / 0.4
  // with probabilities 1/4, 1/2, 1/4, so its SE is sqrt(0.005) = 0.0707 (2,000 resamples: +-2%)
  EXPECT_EQ(table3[1][3], "p2");
  EXPECT_NEAR(std::stod(table3[1][6]), std::sqrt(0.005), 0.004);
  EXPECT_EQ(table3[1][7], "0.200000");
  EXPECT_EQ(table3[1][8], "0.400000");
  EXPECT_NE(u.notes[0].find("2000 resamples of each pooled view-group sample, seed 2008"),
            std::string::npos);
  const stats::Table again = find_table(paper_tables(run_, o), "uncertainty");  // seeded: the same
  ASSERT_EQ(again.rows.size(), u.rows.size());
  for (std::size_t i = 0; i < u.rows.size(); ++i) EXPECT_EQ(texts(again.rows[i]), texts(u.rows[i]));
  o.bootstrap.resamples = 0;
  for (const stats::Table& t : paper_tables(run_, o)) EXPECT_NE(t.file_stem, "uncertainty");
}

TEST_F(PaperTables, QuantileDefinitionHf7) {
  TableOptions o;
  o.quantiles = QuantileDefinition::kHyndmanFan7;
  const std::vector<stats::Table> tables = paper_tables(run_, o);
  const stats::Table& t3 = find_table(tables, "table03_pe");
  EXPECT_NE(t3.title.find("Hyndman-Fan 7"), std::string::npos);
  EXPECT_EQ(t3.rows[0][3].text, "0.30000");
  EXPECT_EQ(t3.rows[0][4].text, "0.25000");
}

TEST_F(PaperTables, VisibilityCounts) {
  const stats::Table t = visibility_table(run_, geometry::Kind::kPoint);
  EXPECT_EQ(t.file_stem, "table02_point_visibility");
  std::vector<std::string> names;
  for (const auto& c : t.columns) names.push_back(c.name);
  EXPECT_EQ(names, (std::vector<std::string>{"Platform", "View", "True visible", "True invisible",
                                             "False visible", "False invisible", "Multiple visible",
                                             "Timeout"}));
  ASSERT_EQ(t.rows.size(), 4u);  // p1 A, B, C; p2 A
  EXPECT_EQ(texts(t.rows[0]), (std::vector<std::string>{"p1", "A", "9", "2", "1", "1", "1", "1"}));
  EXPECT_EQ(texts(t.rows[1]), (std::vector<std::string>{"p1", "B", "0", "2", "0", "0", "0", "0"}));
  EXPECT_EQ(texts(t.rows[2]), (std::vector<std::string>{"p1", "C", "5", "0", "0", "0", "0", "0"}));
  EXPECT_EQ(texts(t.rows[3]), (std::vector<std::string>{"p2", "A", "2", "0", "0", "0", "0", "0"}));
  EXPECT_NE(t.notes[1].find("A = views 1, 2 (FOV 30, window 128)"), std::string::npos);
}

// Shares of the ok records (the timeout apart) with Clopper-Pearson intervals: SciPy 1.10's
// binomtest(k, 14).proportion_ci(0.95, "exact") for p1's group A.
TEST_F(PaperTables, VisibilitySharesWithIntervals) {
  const stats::Table t = visibility_share_table(run_, geometry::Kind::kPoint);
  EXPECT_EQ(t.file_stem, "table02s_point_visibility_shares");
  ASSERT_EQ(t.rows.size(), 4u);
  EXPECT_EQ(texts(t.rows[0]),
            (std::vector<std::string>{"p1", "A", "14", "64.29 (35.14-87.24)", "14.29 (1.78-42.81)",
                                      "7.14 (0.18-33.87)", "7.14 (0.18-33.87)",
                                      "7.14 (0.18-33.87)"}));
  EXPECT_EQ(t.rows[3][6].text, "0.00 (0.00-84.19)");  // p2 A: 0 of 2 false invisible
  EXPECT_EQ(t.rows[0][3].csv, "64.2857143");
}

TEST_F(PaperTables, PhysicalUnitsForSeveralPitches) {
  TableOptions o;
  o.pixel_pitches_mm = {0.255, 1.5};
  const stats::Table t = physical_units_table(run_, GroupSummaries(run_, o.quantiles, 1), o);
  ASSERT_EQ(t.rows.size(), 8u);  // 2 pitches x (A, B, C, all)
  // PE medians of group A: p1 x(5) = 0.30; p2 HF6 of {0.2, 0.4}: 0.2 + 0.5 (0.4 - 0.2), which is
  // 0.30000000000000004 in doubles (0.0765 rounds down for p1, up for p2)
  EXPECT_EQ(texts(t.rows[0]),
            (std::vector<std::string>{"0.255", "A", "30", "128", stats::format_fixed(0.30 * 0.255, 3),
                                      stats::format_fixed((0.2 + 0.5 * (0.4 - 0.2)) * 0.255, 3)}));
  EXPECT_EQ(t.rows[1][4].text, "no data");
  EXPECT_EQ(t.rows[2][4].text, "0.051");  // group C: 0.2 x 0.255
  // all of p1 pooled: group A and five 0.2: 14 values, HF6 median at 7.5 between two 0.2
  EXPECT_EQ(t.rows[3][1].text, "all");
  EXPECT_EQ(t.rows[3][4].text, "0.051");
  EXPECT_EQ(t.rows[4][0].text, "1.5");
  EXPECT_EQ(t.rows[4][4].text, "0.450");
}

TEST_F(PaperTables, CrossPlatformComparison) {
  TableOptions o;
  const GroupSummaries s(run_, o.quantiles, 1);
  const auto rows = compare_platforms(run_, s, o);
  ASSERT_EQ(rows.size(), 2u);  // pe and pe_norm, group A only (p2 has no other group)
  EXPECT_EQ(rows[0].label, "A");
  ASSERT_TRUE(rows[0].a && rows[0].b);
  EXPECT_NEAR(rows[0].a->median - rows[0].b->median, 0.0, 1e-15);
  const stats::Table t = cross_platform_table(run_, rows, o);
  EXPECT_EQ(t.columns[13].name, "IQR a-b");
  EXPECT_EQ(t.rows[0][13].text, "0.125");  // IQR a - b = 0.325 - 0.2
  EXPECT_TRUE(rows[0].comparison.raw.location.defined);
}

TEST_F(PaperTables, NoNaNAnywhere) {
  const std::regex not_a_number(R"(\b-?(nan|inf|infinity)\b)", std::regex::icase);
  TableOptions o;
  const std::vector<stats::Table> tables = paper_tables(run_, o);
  ASSERT_GE(tables.size(), 6u) << "the fixture's run must give the point, line and triangle tables";
  std::size_t cells = 0;
  for (const stats::Table& t : tables) {
    for (const auto& row : t.rows) cells += row.size();
    for (const std::string& text : {stats::render_csv(t), stats::render_markdown(t), stats::render_latex(t)}) {
      EXPECT_FALSE(std::regex_search(text, not_a_number)) << t.file_stem << "\n" << text;
    }
  }
  EXPECT_GT(cells, 100u);  // the check above read real tables, not empty ones
}

// The speed table says what render_us measures on a Vulkan platform only where the run has one.
TEST(PaperTablesSpeed, TheVulkanMeaningOfRenderTimeIsNotedWhereAVulkanPlatformRan) {
  testing::ScopedTempDir gl{"speed_gl"}, vk{"speed_vk"};
  write_records(gl.path, {point("egl-llvmpipe", 1, 0, 0.3), point("egl-llvmpipe", 1, 1, 0.2)});
  write_records(vk.path, {point("egl-llvmpipe", 1, 0, 0.3), point("vk-lavapipe", 1, 0, 0.2)});
  const auto has_note = [](const stats::Table& t) {
    return std::find(t.notes.begin(), t.notes.end(), std::string(kVulkanRenderTimeNote)) !=
           t.notes.end();
  };
  EXPECT_FALSE(has_note(speed_table(load_run_records(gl.path.string()), TableOptions{})));
  EXPECT_TRUE(has_note(speed_table(load_run_records(vk.path.string()), TableOptions{})));
  EXPECT_TRUE(is_vulkan_platform("vk-device:1-msaa4"));
  EXPECT_FALSE(is_vulkan_platform("egl-zink"));
}

TEST(PaperTablesScales, TheScalesOfThePaper) {
  std::map<std::string, int> scale;
  for (const MetricTableSpec& s : metric_table_specs()) scale[s.number] = s.scale_exponent;
  EXPECT_EQ(scale["3"], 0);
  EXPECT_EQ(scale["4"], 3);
  EXPECT_EQ(scale["6"], 6);
  EXPECT_EQ(scale["7"], 3);
  EXPECT_EQ(scale["9"], 6);
  EXPECT_EQ(scale["10"], 3);
}

}  // namespace
}  // namespace ra::analysis
