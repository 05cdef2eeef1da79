// figures.json "speed_error" (speed against error): each point's time and error
// statistics equal those computed here directly from the synthetic records, with the run's
// quantile definition, over the records the header says (time: every `ok` record with a time;
// error: the true-visible ones, normalised unsigned metric).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <nlohmann/json.hpp>

#include "analysis/figure_data.h"
#include "analysis/records_testing.h"

namespace ra::analysis {
namespace {

using nlohmann::json;
using testing::point;
using testing::write_records;

// A line record with an unsigned error; lse_u_norm = lse_u / sqrt(W*H) = lse_u / width.
metrics::Record line(const std::string& platform, int view, std::uint64_t index, double lse_u,
            double render_us) {
  metrics::Record r;
  r.platform = platform;
  testing::set_view(r, view);
  r.kind = "line";
  r.index = index;
  r.visibility = metrics::Visibility::kTrueVisible;
  r.pixels = 10;
  r.lse_s = r.lse_u = lse_u;
  r.lse_s_norm = r.lse_u_norm = lse_u / r.width;
  r.extent_error = 0;
  r.render_us = render_us;
  r.batch_size = 1;
  return r;
}

// Two platforms (the second an antialiasing condition, as it will appear: its own platform name),
// points in views 1-4 (groups A, B) with times and errors that differ by platform and group, some
// records that are not true-visible (a time but no error), and an invalid one (neither counts).
std::vector<metrics::Record> speed_run() {
  std::vector<metrics::Record> rs;
  stats::testing::Generator g(11);
  std::uint64_t i = 0;
  for (const std::string platform : {"osmesa-llvmpipe", "osmesa-llvmpipe-msaa4"}) {
    const double slow = platform == "osmesa-llvmpipe" ? 1 : 3;
    for (int view = 1; view <= 4; ++view) {
      for (int k = 0; k < 41; ++k) {
        metrics::Record r = point(platform, view, i++, 0.1 + 0.6 * g.uniform());
        r.render_us = slow * (5 + 20 * g.uniform()) * (view >= 3 ? 2 : 1);
        r.batch_size = 8;
        rs.push_back(r);
      }
      metrics::Record out = point(platform, view, i++, 0, metrics::Visibility::kTrueInvisible);
      out.render_us = 1000;  // a time without an error: in n_time only
      rs.push_back(out);
      metrics::Record bad = point(platform, view, i++, 0.3, metrics::Visibility::kTrueVisible,
                                  metrics::CaseStatus::kInvalid);
      bad.render_us = 1e6;  // not ok: counted nowhere
      rs.push_back(bad);
    }
  }
  // lines of one platform, group A only
  for (int view = 1; view <= 2; ++view)
    for (int k = 0; k < 3; ++k) rs.push_back(line("osmesa-llvmpipe", view, i++, 1 + k, 10.0 * (k + 1)));
  return rs;
}

struct Expected {
  std::vector<double> time, error;
};

// The samples of each (kind, platform, group), straight from the records.
std::map<std::tuple<std::string, std::string, std::string>, Expected> expected_samples(
    const std::vector<metrics::Record>& rs) {
  std::map<std::tuple<std::string, std::string, std::string>, Expected> out;
  for (const metrics::Record& r : rs) {
    if (r.status != metrics::CaseStatus::kOk) continue;
    Expected& e = out[{r.kind, r.platform, view_group_label(r.view_group)}];
    if (!std::isnan(r.render_us)) e.time.push_back(r.render_us);
    if (r.visibility != metrics::Visibility::kTrueVisible) continue;
    const double v = r.kind == "point" ? r.pe_norm : r.lse_u_norm;
    if (!std::isnan(v)) e.error.push_back(v);
  }
  for (auto& [key, e] : out) {
    std::sort(e.time.begin(), e.time.end());
    std::sort(e.error.begin(), e.error.end());
  }
  return out;
}

void expect_speed_error(const json& doc, const std::vector<metrics::Record>& rs,
                        stats::QuantileDefinition q) {
  const auto expected = expected_samples(rs);
  ASSERT_TRUE(doc.contains("speed_error"));
  ASSERT_EQ(doc["speed_error"].size(), 2u);  // points, lines
  std::size_t points_seen = 0;
  for (const json& entry : doc["speed_error"]) {
    const std::string kind = entry["kind"];
    EXPECT_EQ(entry["metric"], kind == "point" ? "pe_norm" : "lse_u_norm");
    EXPECT_EQ(entry["time_units"], "us");
    for (const json& p : entry["points"]) {
      ++points_seen;
      const auto it =
          expected.find({kind, p["platform"].get<std::string>(), p["view_group"].get<std::string>()});
      ASSERT_NE(it, expected.end()) << p.dump();
      const Expected& e = it->second;
      EXPECT_EQ(p["metric"], entry["metric"]);
      ASSERT_EQ(p["n_time"].get<std::size_t>(), e.time.size()) << p.dump();
      ASSERT_EQ(p["n_error"].get<std::size_t>(), e.error.size()) << p.dump();
      EXPECT_EQ(p["median_us"].get<double>(), stats::quantile_sorted(e.time, 0.5, q));
      EXPECT_EQ(p["q1_us"].get<double>(), stats::quantile_sorted(e.time, 0.25, q));
      EXPECT_EQ(p["q3_us"].get<double>(), stats::quantile_sorted(e.time, 0.75, q));
      EXPECT_EQ(p["median_error"].get<double>(), stats::quantile_sorted(e.error, 0.5, q));
      EXPECT_EQ(p["q1_error"].get<double>(), stats::quantile_sorted(e.error, 0.25, q));
      EXPECT_EQ(p["q3_error"].get<double>(), stats::quantile_sorted(e.error, 0.75, q));
    }
  }
  EXPECT_EQ(points_seen, 2u * 2u + 1u);  // 2 platforms x groups A, B; lines: one group
}

// Why: the figure's points must be the medians of exactly the records the header names, under the
// run's quantile option (as the box plots), for every platform (conditions included).
TEST(SpeedError, PointsAreTheMediansOfTheRecords) {
  const testing::ScopedTempDir scoped("speed_error");
  const std::vector<metrics::Record> rs = speed_run();
  write_records(scoped.path, rs);
  const RunRecords run = load_run_records(scoped.path.string());
  for (auto q : {stats::QuantileDefinition::kHyndmanFan6, stats::QuantileDefinition::kHyndmanFan7}) {
    FigureOptions o;
    o.quantiles = q;
    const json doc = figure_data(run, o);
    EXPECT_EQ(doc["schema_version"], 1);
    expect_speed_error(doc, rs, q);
  }
}

// Why: a hand-computed case, so the test above cannot pass by sharing a mistake with the code.
// Lines of group A: times 10, 20, 30 in each of views 1 and 2 -> 10, 10, 20, 20, 30, 30: median
// 20; HF6 quartiles at positions 1.75 and 5.25: 10 and 30. Errors lse_u 1, 2, 3 (x2) / 128.
TEST(SpeedError, HandComputedLineGroup) {
  const testing::ScopedTempDir scoped("speed_error_hand");
  write_records(scoped.path, speed_run());
  const json doc = figure_data(load_run_records(scoped.path.string()));
  const json& lines = doc["speed_error"][1];
  ASSERT_EQ(lines["kind"], "line");
  ASSERT_EQ(lines["points"].size(), 1u);
  const json& p = lines["points"][0];
  EXPECT_EQ(p["platform"], "osmesa-llvmpipe");
  EXPECT_EQ(p["view_group"], "A");
  EXPECT_EQ(p["views"], json::array({1, 2}));
  EXPECT_EQ(p["width"], 128);
  EXPECT_EQ(p["n_time"], 6);
  EXPECT_DOUBLE_EQ(p["median_us"].get<double>(), 20);
  EXPECT_DOUBLE_EQ(p["q1_us"].get<double>(), 10);
  EXPECT_DOUBLE_EQ(p["q3_us"].get<double>(), 30);
  EXPECT_EQ(p["n_error"], 6);
  EXPECT_DOUBLE_EQ(p["median_error"].get<double>(), 2.0 / 128);
  EXPECT_EQ(lines["symbol"], "LSEu-norm");
  EXPECT_EQ(lines["units"], "sqrt(W*H) units");
}

// Why: a group whose records all lack a time (an older runner, or a platform that does not time)
// still has its error; the missing side is null, never a made-up number.
TEST(SpeedError, AGroupWithoutTimesHasNullTimeStatistics) {
  const testing::ScopedTempDir scoped("speed_error_null");
  std::vector<metrics::Record> rs;
  for (std::uint64_t k = 0; k < 5; ++k) {
    metrics::Record r = point("p", 1, k, 0.1 * double(k + 1));
    r.render_us = metrics::kNA;
    rs.push_back(r);
  }
  write_records(scoped.path, rs);
  const json doc = figure_data(load_run_records(scoped.path.string()));
  const json& p = doc["speed_error"][0]["points"][0];
  EXPECT_EQ(p["n_time"], 0);
  EXPECT_TRUE(p["median_us"].is_null());
  EXPECT_TRUE(p["q3_us"].is_null());
  EXPECT_EQ(p["n_error"], 5);
  EXPECT_DOUBLE_EQ(p["median_error"].get<double>(), 0.3 / 128);
}

}  // namespace
}  // namespace ra::analysis
