// The visibility tables (visibility_tables.cpp): Tables 5 and 8 and the supplements' shares from
// a small synthetic run, against counts made by hand; the status and "Multiple visible" columns
// only where a record needs them; Clopper-Pearson intervals checked where they have a closed form
// (k = 0, k = n - 1, k = n); the point-margin note; a kind without records.
#include "analysis/paper_tables.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "analysis/records_testing.h"

namespace ra::analysis {
namespace {

using metrics::CaseStatus;
using metrics::Visibility;
using testing::point;
using testing::write_records;

metrics::Record line(const std::string& platform, int view, std::uint64_t index,
                     Visibility visibility, CaseStatus status = CaseStatus::kOk) {
  metrics::Record r;
  r.platform = platform;
  testing::set_view(r, view);
  r.kind = "line";
  r.index = index;
  r.status = status;
  r.visibility = visibility;
  r.pixels = visibility == Visibility::kTrueVisible || visibility == Visibility::kFalseVisible ? 6 : 0;
  if (visibility == Visibility::kTrueVisible && status == CaseStatus::kOk) {
    r.lse_s = r.lse_u = 0.25;
    r.lse_s_norm = r.lse_u_norm = 0.25 / r.width;
    r.extent_error = 0;
  }
  r.render_us = 4;
  return r;
}

// p1, group A (views 1, 2): 4 true-visible, 1 true-invisible, 1 invalid, 1 crash (5 ok).
// p1, group B (view 3): 2 false-invisible. p2, group A: 2 true-visible.
std::vector<metrics::Record> line_run() {
  std::uint64_t i = 0;
  return {
      line("p1", 1, i++, Visibility::kTrueVisible),
      line("p1", 1, i++, Visibility::kTrueVisible),
      line("p1", 1, i++, Visibility::kTrueVisible),
      line("p1", 1, i++, Visibility::kTrueInvisible),
      line("p1", 2, i++, Visibility::kTrueVisible),
      line("p1", 2, i++, Visibility::kTrueVisible, CaseStatus::kInvalid),
      line("p1", 2, i++, Visibility::kTrueInvisible, CaseStatus::kCrash),
      line("p1", 3, i++, Visibility::kFalseInvisible),
      line("p1", 3, i++, Visibility::kFalseInvisible),
      line("p2", 1, 0, Visibility::kTrueVisible),
      line("p2", 2, 1, Visibility::kTrueVisible),
  };
}

std::vector<std::string> texts(const std::vector<stats::TableCell>& row) {
  std::vector<std::string> out;
  for (const stats::TableCell& c : row) out.push_back(c.text);
  return out;
}

std::vector<std::string> column_names(const stats::Table& t) {
  std::vector<std::string> out;
  for (const auto& c : t.columns) out.push_back(c.name);
  return out;
}

// Percent with two decimals, as the tables print them.
std::string pct(double share) { return stats::format_fixed(100 * share, 2); }

RunRecords load(const testing::ScopedTempDir& dir, const std::vector<metrics::Record>& rs) {
  write_records(dir.path, rs);
  return load_run_records(dir.path.string());
}

// Invalid and crash records are counted in their own columns, not in a class; there is no
// Timeout column (no record timed out) and no Multiple visible column (no line uses it).
TEST(VisibilityTables, LineCountsPerGroupWithStatusColumnsOnlyWhereUsed) {
  testing::ScopedTempDir dir{"visibility_lines"};
  const RunRecords run = load(dir, line_run());
  const stats::Table t = visibility_table(run, geometry::Kind::kLine);
  EXPECT_EQ(t.file_stem, "table05_line_visibility");
  EXPECT_EQ(t.title.rfind("Table 5 (mirrors the paper's Table 5): the counts of line segments", 0),
            0u)
      << t.title;
  EXPECT_EQ(column_names(t),
            (std::vector<std::string>{"Platform", "View", "True visible", "True invisible",
                                      "False visible", "False invisible", "Invalid", "Crash"}));
  ASSERT_EQ(t.rows.size(), 3u);
  EXPECT_EQ(texts(t.rows[0]), (std::vector<std::string>{"p1", "A", "4", "1", "0", "0", "1", "1"}));
  EXPECT_EQ(texts(t.rows[1]), (std::vector<std::string>{"p1", "B", "0", "0", "0", "2", "0", "0"}));
  EXPECT_EQ(texts(t.rows[2]), (std::vector<std::string>{"p2", "A", "2", "0", "0", "0", "0", "0"}));
  EXPECT_EQ(t.rules_before, (std::vector<std::size_t>{0, 2}));
  EXPECT_EQ(t.notes.size(), 2u);
  EXPECT_NE(t.notes[1].find("A = views 1, 2 (FOV 30, window 128); B = views 3 (FOV 150, window "
                            "128)"),
            std::string::npos)
      << t.notes[1];
}

// One multiple-visible line: the column appears for every row, and a note says the paper uses the
// class for points only. A timeout adds its column.
TEST(VisibilityTables, AMultipleVisibleLineAddsItsColumnAndSaysWhy) {
  testing::ScopedTempDir dir{"visibility_multiple"};
  std::vector<metrics::Record> rs = line_run();
  rs.push_back(line("p2", 1, 7, Visibility::kMultipleVisible));
  rs.push_back(line("p2", 1, 8, Visibility::kTrueVisible, CaseStatus::kTimeout));
  const RunRecords run = load(dir, rs);
  const stats::Table t = visibility_table(run, geometry::Kind::kLine);
  EXPECT_EQ(column_names(t),
            (std::vector<std::string>{"Platform", "View", "True visible", "True invisible",
                                      "False visible", "False invisible", "Multiple visible",
                                      "Invalid", "Crash", "Timeout"}));
  EXPECT_EQ(texts(t.rows[0]),
            (std::vector<std::string>{"p1", "A", "4", "1", "0", "0", "0", "1", "1", "0"}));
  EXPECT_EQ(texts(t.rows[2]),
            (std::vector<std::string>{"p2", "A", "2", "0", "0", "0", "1", "0", "0", "1"}));
  ASSERT_EQ(t.notes.size(), 3u);
  EXPECT_EQ(t.notes[2],
            "Multiple visible is shown because the records use it for this kind (the paper uses it "
            "for points only).");
}

// Shares of the ok records (invalid and crash apart): p1 A has 5, B 2, p2 A 2. Where the
// Clopper-Pearson 95% interval has a closed form: k = 0 of n: [0, 1 - 0.025^(1/n)]; k = n:
// [0.025^(1/n), 1]; k = n - 1: upper 0.975^(1/n); k = 1: lower 1 - 0.975^(1/n).
TEST(VisibilityTables, SharesArePercentagesOfOkRecordsWithExactIntervals) {
  testing::ScopedTempDir dir{"visibility_shares"};
  const RunRecords run = load(dir, line_run());
  const stats::Table t = visibility_share_table(run, geometry::Kind::kLine);
  EXPECT_EQ(t.file_stem, "table05s_line_visibility_shares");
  EXPECT_EQ(column_names(t),
            (std::vector<std::string>{"Platform", "View", "Records", "True visible",
                                      "True invisible", "False visible", "False invisible"}));
  ASSERT_EQ(t.rows.size(), 3u);
  EXPECT_EQ(t.rows[0][2].text, "5");
  const std::string tv = t.rows[0][3].text, ti = t.rows[0][4].text;
  EXPECT_EQ(tv.rfind("80.00 (", 0), 0u) << tv;
  EXPECT_EQ(tv.substr(tv.size() - 7), "-" + pct(std::pow(0.975, 1 / 5.0)) + ")") << tv;
  EXPECT_EQ(ti.rfind("20.00 (" + pct(1 - std::pow(0.975, 1 / 5.0)) + "-", 0), 0u) << ti;
  const std::string zero_of_5 = "0.00 (0.00-" + pct(1 - std::pow(0.025, 1 / 5.0)) + ")";
  EXPECT_EQ(t.rows[0][5].text, zero_of_5);
  EXPECT_EQ(t.rows[0][6].text, zero_of_5);
  EXPECT_EQ(zero_of_5, "0.00 (0.00-52.18)");
  // p1 B: 2 of 2 false invisible; p2 A: 2 of 2 true visible.
  const std::string all_of_2 = "100.00 (" + pct(std::pow(0.025, 0.5)) + "-100.00)";
  const std::string none_of_2 = "0.00 (0.00-" + pct(1 - std::pow(0.025, 0.5)) + ")";
  EXPECT_EQ(texts(t.rows[1]), (std::vector<std::string>{"p1", "B", "2", none_of_2, none_of_2,
                                                        none_of_2, all_of_2}));
  EXPECT_EQ(texts(t.rows[2]), (std::vector<std::string>{"p2", "A", "2", all_of_2, none_of_2,
                                                        none_of_2, none_of_2}));
  EXPECT_EQ(all_of_2, "100.00 (15.81-100.00)");
  // CSV: the share alone.
  EXPECT_EQ(t.rows[0][3].csv, "80");
  EXPECT_EQ(t.rows[1][6].csv, "100");
}

// Points always have the Multiple visible column (the paper's Table 2 has it); with the paper's
// point convention applied, a note says how many true-invisible points became false-invisible.
TEST(VisibilityTables, PointsHaveTheMultipleColumnAndNameTheMarginConvention) {
  testing::ScopedTempDir dir{"visibility_points"};
  RunRecords run = load(dir, {point("p1", 1, 0, 0.2), point("p1", 2, 1, 0.3),
                              point("p1", 1, 2, 0, Visibility::kFalseInvisible)});
  stats::Table t = visibility_table(run, geometry::Kind::kPoint);
  EXPECT_EQ(t.file_stem, "table02_point_visibility");
  EXPECT_EQ(t.columns.back().name, "Multiple visible");
  EXPECT_EQ(texts(t.rows[0]), (std::vector<std::string>{"p1", "A", "2", "0", "0", "1", "0"}));
  EXPECT_EQ(t.notes.size(), 2u);
  run.point_margin_px = 0.5;
  run.points_within_margin = 1;
  t = visibility_table(run, geometry::Kind::kPoint);
  ASSERT_EQ(t.notes.size(), 3u);
  EXPECT_EQ(t.notes[2],
            "The paper's point convention (--point-margin-px 0.5): 1 true-invisible points whose "
            "projection lies within that many pixels outside the window are counted "
            "false-invisible (docs/method.md, \"Where we differ from the paper\").");
  EXPECT_EQ(visibility_share_table(run, geometry::Kind::kPoint).columns.back().name,
            "Multiple visible");
}

// A kind the run has no record of: the table has its name and header columns and no rows.
TEST(VisibilityTables, AKindWithoutRecordsHasNoRows) {
  testing::ScopedTempDir dir{"visibility_empty"};
  const RunRecords run = load(dir, line_run());
  const stats::Table t = visibility_table(run, geometry::Kind::kTriangle);
  EXPECT_EQ(t.file_stem, "table08_triangle_visibility");
  EXPECT_TRUE(t.rows.empty());
  EXPECT_EQ(t.columns.size(), 6u);
  const stats::Table s = visibility_share_table(run, geometry::Kind::kTriangle);
  EXPECT_EQ(s.file_stem, "table08s_triangle_visibility_shares");
  EXPECT_TRUE(s.rows.empty());
}

}  // namespace
}  // namespace ra::analysis
