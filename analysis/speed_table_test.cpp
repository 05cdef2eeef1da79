// The speed table (speed_table.cpp): render time beside error per platform, kind and view group
// and all groups pooled, against Hyndman-Fan 6 (and 7) medians and IQRs computed by hand; which
// records count as cases (ok, with a time) and which carry the error (true-visible, with a value);
// a group without any time or error; each kind's headline error and its decimals.
#include "analysis/paper_tables.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "analysis/records_testing.h"

namespace ra::analysis {
namespace {

using metrics::CaseStatus;
using metrics::Visibility;
using testing::point;
using testing::write_records;

constexpr double kNoTime = std::numeric_limits<double>::quiet_NaN();

metrics::Record timed(metrics::Record r, double render_us) {
  r.render_us = render_us;
  return r;
}

metrics::Record line(const std::string& platform, int view, std::uint64_t index, double lse_u,
                     double render_us) {
  metrics::Record r;
  r.platform = platform;
  testing::set_view(r, view);
  r.kind = "line";
  r.index = index;
  r.visibility = Visibility::kTrueVisible;
  r.pixels = 8;
  r.lse_s = r.lse_u = lse_u;
  r.lse_s_norm = r.lse_u_norm = lse_u / r.width;
  r.extent_error = 0;
  r.render_us = render_us;
  return r;
}

// p1 points, group A: true-visible PE 0.25, 0.5, 0.75 (view 1) and 1.0 (view 2) drawn in 10, 20,
//   40 and 30 us; a true-visible PE 0.125 without a time; a true-invisible point of 100 us; an
//   invalid one of 10^6 us (counted nowhere).
//   Cases: 10 20 30 40 100, HF6 median 30, Q1 at 1.5 = 15, Q3 at 4.5 = 70, IQR 55.
//   True visible: 10 20 30 40, median 25, Q1 at 1.25 = 12.5, Q3 at 3.75 = 37.5, IQR 25.
//   PE: 0.125 0.25 0.5 0.75 1.0, median 0.5, Q1 0.1875, Q3 0.875, IQR 0.6875.
// p1 points, group B: PE 0.5 in 7 us (n = 1).
//   All of p1's points: cases 7 10 20 30 40 100, median at 3.5 = 25, Q1 at 1.75 = 9.25, Q3 at
//   5.25 = 55, IQR 45.75; visible 7 10 20 30 40: median 20, Q1 8.5, Q3 35, IQR 26.5; PE 0.125 0.25
//   0.5 0.5 0.75 1.0: median 0.5, Q1 at 1.75 = 0.21875, Q3 at 5.25 = 0.8125, IQR 0.59375.
// p1 lines, group A: LSEu 0.25 in 3 us, 0.75 in 5 us: medians 4 us and 0.5 px, quartiles clamped
//   to the extremes, IQRs 2 us and 0.5 px.
// p2 points, group A: one true-invisible point without a time.
std::vector<metrics::Record> speed_run() {
  std::uint64_t i = 0;
  return {
      timed(point("p1", 1, i++, 0.25), 10),
      timed(point("p1", 1, i++, 0.5), 20),
      timed(point("p1", 1, i++, 0.75), 40),
      timed(point("p1", 1, i++, 0.125), kNoTime),
      timed(point("p1", 1, i++, 0, Visibility::kTrueInvisible), 100),
      timed(point("p1", 1, i++, 0.3, Visibility::kTrueVisible, CaseStatus::kInvalid), 1e6),
      timed(point("p1", 2, i++, 1.0), 30),
      timed(point("p1", 3, i++, 0.5), 7),
      line("p1", 1, 0, 0.25, 3),
      line("p1", 1, 1, 0.75, 5),
      timed(point("p2", 1, 0, 0, Visibility::kTrueInvisible), kNoTime),
  };
}

std::vector<std::string> texts(const std::vector<stats::TableCell>& row) {
  std::vector<std::string> out;
  for (const stats::TableCell& c : row) out.push_back(c.text);
  return out;
}

class SpeedTable : public ::testing::Test {
 protected:
  void SetUp() override {
    write_records(dir_.path, speed_run());
    run_ = load_run_records(dir_.path.string());
  }
  stats::Table table(stats::QuantileDefinition q = stats::QuantileDefinition::kHyndmanFan6) {
    TableOptions o;
    o.quantiles = q;
    o.jobs = 1;
    return speed_table(run_, o);
  }
  testing::ScopedTempDir dir_{"speed_table"};
  RunRecords run_;
};

TEST_F(SpeedTable, TimesAndErrorsAreTheHandComputedMediansOfEachGroupAndOfAll) {
  const stats::Table t = table();
  EXPECT_EQ(t.file_stem, "speed");
  ASSERT_EQ(t.columns.size(), 14u);
  EXPECT_EQ(t.columns[5].name, "Cases");
  EXPECT_EQ(t.columns[8].name, "True visible");
  ASSERT_EQ(t.rows.size(), 7u);  // p1: points A, B, all; lines A, all. p2: points A, all
  EXPECT_EQ(texts(t.rows[0]),
            (std::vector<std::string>{"p1", "point", "A", "30", "128", "5", "30.00", "55.00", "4",
                                      "25.00", "25.00", "PE (px)", "0.50000", "0.68750"}));
  EXPECT_EQ(texts(t.rows[1]),
            (std::vector<std::string>{"p1", "point", "B", "150", "128", "1", "7.00", "0.00", "1",
                                      "7.00", "0.00", "PE (px)", "0.50000", "0.00000"}));
  EXPECT_EQ(texts(t.rows[2]),
            (std::vector<std::string>{"p1", "point", "all", "", "", "6", "25.00", "45.75", "5",
                                      "20.00", "26.50", "PE (px)", "0.50000", "0.59375"}));
  EXPECT_EQ(texts(t.rows[3]),
            (std::vector<std::string>{"p1", "line", "A", "30", "128", "2", "4.00", "2.00", "2",
                                      "4.00", "2.00", "LSEu (px)", "0.5000", "0.5000"}));
  EXPECT_EQ(texts(t.rows[4]),
            (std::vector<std::string>{"p1", "line", "all", "", "", "2", "4.00", "2.00", "2",
                                      "4.00", "2.00", "LSEu (px)", "0.5000", "0.5000"}));
  // a rule above each platform's first row
  EXPECT_EQ(t.rules_before, (std::vector<std::size_t>{0, 5}));
}

// A group whose records have neither a time nor an error value: zero cases and "no data", never
// NaN.
TEST_F(SpeedTable, AGroupWithoutTimesOrErrorsSaysNoData) {
  const stats::Table t = table();
  const std::vector<std::string> none = {"p2", "point", "A", "30", "128", "0", "no data",
                                         "no data", "0", "no data", "no data", "PE (px)",
                                         "no data", "no data"};
  EXPECT_EQ(texts(t.rows[5]), none);
  std::vector<std::string> all = none;
  all[2] = "all";
  all[3] = all[4] = "";
  EXPECT_EQ(texts(t.rows[6]), all);
}

// Hyndman-Fan 7 puts group A's quartiles of 10 20 30 40 100 on order statistics 2 and 4: IQR 20;
// the median stays 30. The title says which definition.
TEST_F(SpeedTable, TheQuantileDefinitionChangesTheQuartiles) {
  const stats::Table t = table(stats::QuantileDefinition::kHyndmanFan7);
  EXPECT_NE(t.title.find("Hyndman-Fan 7"), std::string::npos);
  EXPECT_EQ(t.rows[0][6].text, "30.00");
  EXPECT_EQ(t.rows[0][7].text, "20.00");
  EXPECT_NE(table().title.find("Hyndman-Fan 6"), std::string::npos);
}

// Triangles show TEu in px^2 with 3 decimals; without a Vulkan platform the notes say nothing of
// Vulkan.
TEST(SpeedTableKinds, EachKindShowsItsHeadlineErrorWithThePapersDecimals) {
  testing::ScopedTempDir dir{"speed_table_kinds"};
  metrics::Record t;
  t.platform = "p1";
  testing::set_view(t, 1);
  t.kind = "triangle";
  t.visibility = Visibility::kTrueVisible;
  t.pixels = 30;
  t.te_s = t.te_u = 1.5;
  t.te_s_norm = t.te_u_norm = 1.5 / (128 * 128);
  t.te_u_edge_norm = 0.1;
  t.render_us = 12.5;
  write_records(dir.path, {t});
  const RunRecords run = load_run_records(dir.path.string());
  const stats::Table table = speed_table(run, TableOptions{});
  ASSERT_EQ(table.rows.size(), 2u);
  EXPECT_EQ(texts(table.rows[0]),
            (std::vector<std::string>{"p1", "triangle", "A", "30", "128", "1", "12.50", "0.00",
                                      "1", "12.50", "0.00", "TEu (px^2)", "1.500", "0.000"}));
  EXPECT_EQ(table.notes.size(), 3u);
  EXPECT_EQ(table.notes[2], kDeviceClockNote);
  EXPECT_EQ(table.notes[0],
            "Cases: records with status ok and a render time; True visible: those of them that "
            "are true-visible (the error is measured on these).");
}

}  // namespace
}  // namespace ra::analysis
