// The metric tables (metric_tables.cpp) of lines and triangles from a small synthetic run: Tables
// 6, 7, 9, 10 and their supplements against Hyndman-Fan 6 medians and IQRs computed by hand over
// pooled views (dyadic values, so every number is exact), a group of one value, records that must
// not count, empty cells and groups without values, Table 11's conversion, and the clip-plane
// columns.
#include "analysis/paper_tables.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "analysis/records_testing.h"

namespace ra::analysis {
namespace {

using metrics::CaseStatus;
using metrics::Visibility;
using stats::QuantileDefinition;
using testing::write_records;

// A line with signed and unsigned errors in pixels; the normalised ones divide by sqrt(W*H).
metrics::Record line(const std::string& platform, int view, std::uint64_t index, double lse_s,
                     double lse_u, Visibility visibility = Visibility::kTrueVisible,
                     CaseStatus status = CaseStatus::kOk) {
  metrics::Record r;
  r.platform = platform;
  testing::set_view(r, view);
  r.kind = "line";
  r.index = index;
  r.status = status;
  r.visibility = visibility;
  r.pixels = 10;
  r.lse_s = lse_s;
  r.lse_u = lse_u;
  r.lse_s_norm = lse_s / r.width;
  r.lse_u_norm = lse_u / r.width;
  r.extent_error = 0;
  r.render_us = 5;
  return r;
}

// A triangle with signed and unsigned area errors in px^2; the normalised ones divide by W*H.
metrics::Record triangle(const std::string& platform, int view, std::uint64_t index, double te_s,
                         double te_u) {
  metrics::Record r;
  r.platform = platform;
  testing::set_view(r, view);
  r.kind = "triangle";
  r.index = index;
  r.visibility = Visibility::kTrueVisible;
  r.pixels = 40;
  r.te_s = te_s;
  r.te_u = te_u;
  r.te_s_norm = te_s / (r.width * r.height);
  r.te_u_norm = te_u / (r.width * r.height);
  r.te_u_edge_norm = te_u / 40;
  r.render_us = 7;
  return r;
}

// Platform p1, lines:
//   group A (views 1, 2): LSEu {0.25, 0.75, 0.5} + {1.0, 0.375}, pooled 0.25 0.375 0.5 0.75 1.0:
//     HF6 median x(3) = 0.5, Q1 at 1.5 = 0.3125, Q3 at 4.5 = 0.875, IQR 0.5625;
//     LSEs {-0.125, 0.75, -0.5} + {1.0, -0.375}, pooled -0.5 -0.375 -0.125 0.75 1.0:
//     median -0.125, Q1 -0.4375, Q3 0.875, IQR 1.3125.
//     Also in view 1: a false-visible and a timed-out line with errors of 100 (they must not count).
//   group B (views 3, 4): one line of LSEu 0.6875 (n = 1: median 0.6875, IQR 0), and a
//     true-visible line without values (not measured).
// Platform p2, lines: group C (view 5, window 907) LSEu {0.5, 1.5}: HF6 median 1.0, quartiles at
//   0.75 and 2.25 clamp to 0.5 and 1.5, IQR 1.0.
// Platform p1, triangles: group A TEu {2, 4, 10} + {6}, pooled 2 4 6 10: median at 2.5 = 5, Q1 at
//   1.25 = 2.5, Q3 at 3.75 = 9, IQR 6.5; TEs {-2, 4, -10} + {6}, pooled -10 -2 4 6: median 1,
//   Q1 -8, Q3 5.5, IQR 13.5.
std::vector<metrics::Record> line_triangle_run() {
  std::vector<metrics::Record> rs;
  std::uint64_t i = 0;
  rs.push_back(line("p1", 1, i++, -0.125, 0.25));
  rs.push_back(line("p1", 1, i++, 0.75, 0.75));
  rs.push_back(line("p1", 1, i++, -0.5, 0.5));
  rs.push_back(line("p1", 2, i++, 1.0, 1.0));
  rs.push_back(line("p1", 2, i++, -0.375, 0.375));
  rs.push_back(line("p1", 1, i++, 100, 100, Visibility::kFalseVisible));
  rs.push_back(line("p1", 1, i++, 100, 100, Visibility::kTrueVisible, CaseStatus::kTimeout));
  rs.push_back(line("p1", 3, i++, 0.6875, 0.6875));
  rs.push_back(testing::unmeasured_line("p1", 4, i++));
  rs.push_back(line("p2", 5, 0, 0.5, 0.5));
  rs.push_back(line("p2", 5, 1, -1.5, 1.5));
  std::uint64_t t = 0;
  rs.push_back(triangle("p1", 1, t++, -2, 2));
  rs.push_back(triangle("p1", 1, t++, 4, 4));
  rs.push_back(triangle("p1", 1, t++, -10, 10));
  rs.push_back(triangle("p1", 2, t++, 6, 6));
  return rs;
}

const MetricTableSpec& spec(const std::string& number) {
  for (const MetricTableSpec& s : metric_table_specs())
    if (s.number == number) return s;
  throw std::runtime_error("no table " + number);
}

std::vector<std::string> texts(const std::vector<stats::TableCell>& row) {
  std::vector<std::string> out;
  for (const stats::TableCell& c : row) out.push_back(c.text);
  return out;
}

bool has_note(const stats::Table& t, const std::string& text) {
  for (const std::string& n : t.notes)
    if (n.find(text) != std::string::npos) return true;
  return false;
}

class MetricTables : public ::testing::Test {
 protected:
  void SetUp() override {
    write_records(dir_.path, line_triangle_run());
    run_ = load_run_records(dir_.path.string());
    summaries_.emplace(run_, QuantileDefinition::kHyndmanFan6, 1);
  }
  stats::Table table(const std::string& number) {
    return metric_table(run_, *summaries_, spec(number), QuantileDefinition::kHyndmanFan6);
  }
  testing::ScopedTempDir dir_{"metric_tables"};
  RunRecords run_;
  std::optional<GroupSummaries> summaries_;
};

// Table 7s in pixels and Table 7 in sqrt(W*H) units x10^3: one row per view group, one column
// pair per platform. 0.5 / 128 x 1000 = 3.90625; 0.5625 / 128 x 1000 = 4.39453125; 0.6875 / 128
// x 1000 = 5.37109375; 1.0 / 907 x 1000 = 1.1025...
TEST_F(MetricTables, LineTablesAreTheHandComputedMedianAndIqrOfThePooledViews) {
  const stats::Table t7s = table("7s");
  EXPECT_EQ(t7s.file_stem, "table07s_lse_u");
  EXPECT_NE(t7s.title.find("Table 7s (supplement to the paper's Table 7)"), std::string::npos);
  ASSERT_EQ(t7s.rows.size(), 3u);
  EXPECT_EQ(texts(t7s.rows[0]), (std::vector<std::string>{"A", "30", "128", "0.5000", "0.5625",
                                                          "no data", "no data"}));
  EXPECT_EQ(texts(t7s.rows[1]), (std::vector<std::string>{"B", "150", "128", "0.6875", "0.0000",
                                                          "no data", "no data"}));
  EXPECT_EQ(texts(t7s.rows[2]), (std::vector<std::string>{"C", "30", "907", "no data", "no data",
                                                          "1.0000", "1.0000"}));
  const stats::Table t7 = table("7");
  EXPECT_NE(t7.title.find("Table 7 (mirrors the paper's Table 7)"), std::string::npos);
  EXPECT_NE(t7.title.find("x10^3"), std::string::npos);
  EXPECT_EQ(texts(t7.rows[0]), (std::vector<std::string>{"A", "30", "128", "3.906", "4.395",
                                                         "no data", "no data"}));
  EXPECT_EQ(t7.rows[0][4].csv, "4.39453125");
  EXPECT_EQ(t7.rows[1][3].text, "5.371");
  EXPECT_EQ(t7.rows[2][5].text, "1.103");
  ASSERT_EQ(t7.groups.size(), 3u);
  EXPECT_EQ(t7.groups[1].label, "p1");
  EXPECT_EQ(t7.groups[2].label, "p2");
}

// Signed errors keep their sign; Table 6 shows x10^6 with 2 decimals, Table 9 too (W*H units).
// -0.125 / 128 x 10^6 = -976.5625; 1.3125 / 128 x 10^6 = 10253.90625; 1 / 16384 x 10^6 =
// 61.03515625; 13.5 / 16384 x 10^6 = 823.974609375.
TEST_F(MetricTables, SignedErrorsKeepTheirSignAndThePapersScale) {
  const stats::Table t6s = table("6s");
  EXPECT_EQ(t6s.rows[0][3].text, "-0.1250");
  EXPECT_EQ(t6s.rows[0][4].text, "1.3125");
  const stats::Table t6 = table("6");
  EXPECT_EQ(t6.rows[0][3].text, "-976.56");
  EXPECT_EQ(t6.rows[0][4].text, "10253.91");
  EXPECT_EQ(t6.rows[2][5].text, "-551.27");  // p2's C: LSEs {-1.5, 0.5}, median -0.5 / 907 x 10^6
  const stats::Table t9s = table("9s");
  ASSERT_EQ(t9s.rows.size(), 1u);  // triangles only in group A, of p1 only; p2 has a column
  EXPECT_EQ(texts(t9s.rows[0]), (std::vector<std::string>{"A", "30", "128", "1.000", "13.500",
                                                          "no data", "no data"}));
  const stats::Table t9 = table("9");
  EXPECT_EQ(texts(t9.rows[0]), (std::vector<std::string>{"A", "30", "128", "61.04", "823.97",
                                                         "no data", "no data"}));
  // Table 10 and 10s: unsigned; 5 / 16384 x 10^3 = 0.30517578125, 6.5 / 16384 x 10^3 = 0.3967...
  EXPECT_EQ(texts(table("10").rows[0]), (std::vector<std::string>{"A", "30", "128", "0.305",
                                                                  "0.397", "no data", "no data"}));
  EXPECT_EQ(texts(table("10s").rows[0]), (std::vector<std::string>{"A", "30", "128", "5.000",
                                                                   "6.500", "no data", "no data"}));
  // TEu per pixel of visible edge (here TEu / 40): {0.05, 0.1, 0.15, 0.25}, median 0.125, Q1 at
  // 1.25 = 0.0625, Q3 at 3.75 = 0.225, IQR 0.1625
  EXPECT_EQ(texts(table("10e").rows[0]), (std::vector<std::string>{"A", "30", "128", "0.1250",
                                                                   "0.1625", "no data", "no data"}));
}

// The false-visible and timed-out lines of 100 px did not move the medians (checked above); the
// line without values is counted in a note; a cell without values says "no data" and why; the
// group note names the views pooled.
TEST_F(MetricTables, EmptyCellsAndRecordsWithoutValuesAreSaidNotGuessed) {
  const stats::Table t7 = table("7");
  EXPECT_TRUE(has_note(t7, "1 true-visible records have no value of lse_u_norm (not measured by "
                           "the runner that wrote them)."));
  EXPECT_TRUE(has_note(t7, "no data: no true-visible record of this view group and platform has a "
                           "value."));
  EXPECT_TRUE(has_note(t7, "A = views 1, 2 (FOV 30, window 128); B = views 3, 4 (FOV 150, window "
                           "128); C = views 5 (FOV 30, window 907)"));
  EXPECT_TRUE(has_note(t7, "Sample: true-visible line segments with status ok and a value of "
                           "lse_u_norm."));
  // Triangles: every true-visible one has its values; only p2, which drew none, lacks data.
  const stats::Table t10 = table("10");
  EXPECT_TRUE(has_note(t10, "no data"));
  EXPECT_FALSE(has_note(t10, "have no value"));
  for (const stats::Table& t : {table("6"), table("7"), table("9"), table("10")})
    for (const auto& row : t.rows)
      for (const stats::TableCell& c : row)
        EXPECT_EQ(c.text.find("nan"), std::string::npos) << t.file_stem;
}

// Table 11 without points: LSEu (mm) and TEu (mm^2) per platform, for each pitch; mm = px x pitch,
// mm^2 = px^2 x pitch^2. At 0.5 mm: A's LSEu 0.5 -> 0.250, TEu 5 -> 1.25; B's LSEu 0.6875 ->
// 0.34375. "all" pools p1's groups: LSEu 0.25 0.375 0.5 0.6875 0.75 1.0, HF6 median at 3.5 =
// 0.59375 -> 0.297 mm.
TEST_F(MetricTables, PhysicalUnitsConvertTheMediansByThePitch) {
  TableOptions o;
  o.pixel_pitches_mm = {0.5, 2};
  o.jobs = 1;
  const stats::Table t = physical_units_table(run_, *summaries_, o);
  std::vector<std::string> names;
  for (const auto& c : t.columns) names.push_back(c.name);
  EXPECT_EQ(names, (std::vector<std::string>{"Pitch (mm)", "View", "FOV", "Win Size", "LSEu (mm)",
                                             "TEu (mm^2)", "LSEu (mm)", "TEu (mm^2)"}));
  ASSERT_EQ(t.rows.size(), 8u);  // 2 pitches x (A, B, C, all)
  EXPECT_EQ(texts(t.rows[0]), (std::vector<std::string>{"0.5", "A", "30", "128", "0.250", "1.25",
                                                        "no data", "no data"}));
  EXPECT_EQ(texts(t.rows[1]), (std::vector<std::string>{"0.5", "B", "150", "128", "0.344",
                                                        "no data", "no data", "no data"}));
  EXPECT_EQ(texts(t.rows[2]), (std::vector<std::string>{"0.5", "C", "30", "907", "no data",
                                                        "no data", "0.500", "no data"}));
  EXPECT_EQ(texts(t.rows[3]), (std::vector<std::string>{"0.5", "all", "", "", "0.297", "1.25",
                                                        "0.500", "no data"}));
  EXPECT_EQ(t.rows[4][4].text, "1.000");  // 0.5 px x 2 mm
  EXPECT_EQ(t.rows[4][5].text, "20.00");  // 5 px^2 x 4 mm^2
  EXPECT_EQ(t.rules_before, (std::vector<std::size_t>{0, 4}));
  EXPECT_TRUE(has_note(t, "no data: no true-visible record with a value."));
}

// Views whose groups differ in their clip planes: Near and Far columns after the window; without
// a difference, none.
TEST(MetricTablesPlanes, NearAndFarAppearOnlyWhenTheGroupsDifferInThem) {
  testing::ScopedTempDir dir{"metric_tables_planes"};
  std::vector<metrics::Record> rs = {line("p1", 1, 0, 0.25, 0.25), line("p1", 3, 1, 0.5, 0.5)};
  write_records(dir.path, rs);
  RunRecords same = load_run_records(dir.path.string());
  const stats::Table plain = metric_table(same, GroupSummaries(same, QuantileDefinition::kHyndmanFan6, 1),
                                          spec("7s"), QuantileDefinition::kHyndmanFan6);
  EXPECT_EQ(plain.columns.size(), 5u);
  EXPECT_EQ(plain.groups.front().span, 3u);

  testing::ScopedTempDir other{"metric_tables_planes_differ"};
  rs[1].near = 1e-5;
  rs[1].far = 100;
  write_records(other.path, rs);
  RunRecords differ = load_run_records(other.path.string());
  const stats::Table t = metric_table(differ, GroupSummaries(differ, QuantileDefinition::kHyndmanFan6, 1),
                                      spec("7s"), QuantileDefinition::kHyndmanFan6);
  ASSERT_EQ(t.columns.size(), 7u);
  EXPECT_EQ(t.columns[3].name, "Near");
  EXPECT_EQ(t.columns[4].name, "Far");
  EXPECT_EQ(t.groups.front().span, 5u);
  EXPECT_EQ(texts(t.rows[0]), (std::vector<std::string>{"A", "30", "128", "0.01", "10", "0.2500",
                                                        "0.0000"}));
  EXPECT_EQ(texts(t.rows[1]), (std::vector<std::string>{"B", "150", "128", "1e-05", "100",
                                                        "0.5000", "0.0000"}));
}

}  // namespace
}  // namespace ra::analysis
