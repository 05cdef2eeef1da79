// The first summary of a run (run_summary.cpp): one Markdown row per platform, kind and view with
// the visibility counts, the headline metric's Hyndman-Fan 6 median and IQR, the share equal to
// the reference and the median render time, checked against values computed by hand; empty cells
// and missing times as "n/a"; several records files; the cost paragraph from the manifest.
#include "analysis/run_summary.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "analysis/records_testing.h"
#include "rundir/manifest.h"
#include "rundir/run_folder.h"

namespace ra::analysis {
namespace {

using metrics::CaseStatus;
using metrics::Visibility;
using testing::lines_of;
using testing::point;
using testing::write_records;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

metrics::Record with(metrics::Record r, double render_us, std::int64_t ref_diff = -1) {
  r.render_us = render_us;
  r.ref_diff = ref_diff;
  return r;
}

metrics::Record line(std::uint64_t index, double lse_u_norm) {
  metrics::Record r;
  r.platform = "p1";
  testing::set_view(r, 2);
  r.kind = "line";
  r.index = index;
  r.visibility = Visibility::kTrueVisible;
  r.pixels = 9;
  r.lse_u_norm = lse_u_norm;
  r.lse_u = lse_u_norm * r.width;
  r.render_us = kNaN;
  return r;
}

// p1 points, view 1: true-visible PE 0.25, 0.5, 1.0 (reference differences 0, 0, 3), one each
// of true-invisible, false-visible, false-invisible, and an invalid record. PE: HF6 median x(2) =
// 0.5, quartiles at 1 and 3: 0.25 and 1.0, IQR 0.75. Equal to the reference: 2 of the 3 compared
// (66.67%). Times of the ok records 10 12 14 16 18 30: median at 3.5 = 15.
// p1 lines, view 2: LSEu-norm 0.0625 and one without a value; no time, no comparison.
// p1 triangles, view 3: one true-invisible, 5 us.
std::vector<metrics::Record> points_file() {
  return {
      with(point("p1", 1, 0, 0.25), 10, 0),
      with(point("p1", 1, 1, 0.5), 14, 0),
      with(point("p1", 1, 2, 1.0), 30, 3),
      with(point("p1", 1, 3, 0, Visibility::kTrueInvisible), 12),
      with(point("p1", 1, 4, 0, Visibility::kFalseVisible), 16),
      with(point("p1", 1, 5, 0, Visibility::kFalseInvisible), 18),
      with(point("p1", 1, 6, 0, Visibility::kTrueVisible, CaseStatus::kInvalid), 1e6, 5),
  };
}

std::vector<metrics::Record> other_file() {
  metrics::Record t;
  t.platform = "p1";
  testing::set_view(t, 3);
  t.kind = "triangle";
  t.visibility = Visibility::kTrueInvisible;
  t.render_us = 5;
  return {line(0, 0.0625), line(1, kNaN), t};
}

// The table's rows: its lines but the header and the rule.
std::vector<std::string> rows_of(const std::string& md) {
  std::vector<std::string> rows;
  for (const std::string& l : lines_of(md))
    if (l.rfind("| ", 0) == 0 && l.rfind("| platform ", 0) != 0 && l.find("---") == std::string::npos)
      rows.push_back(l);
  return rows;
}

TEST(RunSummary, RowsAreTheHandComputedCountsMediansAndSharesPerPlatformKindAndView) {
  testing::ScopedTempDir dir{"run_summary"};
  write_records(dir.path, points_file(), "a.csv");
  write_records(dir.path, other_file(), "b.csv");
  const std::string md = write_run_summary(dir.path.string());
  EXPECT_EQ(md.rfind("# Run summary: " + dir.path.string() + "\n\n", 0), 0u) << md;
  EXPECT_NE(md.find("| platform | kind | view | FOV | window | true-vis | true-invis | false-vis "
                    "| false-invis | multiple | invalid/failed | metric | median | IQR | "
                    "ref-equal | median us |\n"),
            std::string::npos);
  // In (platform, kind, view) order: "line" < "point" < "triangle".
  EXPECT_EQ(rows_of(md),
            (std::vector<std::string>{
                "| p1 | line | 2 | 30 | 128x128 | 2 | 0 | 0 | 0 | 0 | 0 | LSEu-norm | 0.0625 | 0 "
                "| n/a | n/a |",
                "| p1 | point | 1 | 30 | 128x128 | 3 | 1 | 1 | 1 | 0 | 1 | PE (px) | 0.5 | 0.75 | "
                "66.67% | 15.0 |",
                "| p1 | triangle | 3 | 150 | 128x128 | 0 | 1 | 0 | 0 | 0 | 0 | TEu-norm | n/a | "
                "n/a | n/a | 5.0 |"}));
  // No manifest: no cost paragraph; the file holds what was returned.
  EXPECT_EQ(md.find("Drawing"), std::string::npos);
  EXPECT_EQ(testing::read_text(rundir::run_folder::summary(dir.path.string())), md);
}

// Unfinished shards (*.csv.tmp) are not read; a second platform gets rows of its own, in name
// order, and a view in which every compared record differs from the reference reads 0.00%.
TEST(RunSummary, OnlyFinishedRecordsFilesAreReadAndPlatformsComeInNameOrder) {
  testing::ScopedTempDir dir{"run_summary_platforms"};
  write_records(dir.path, {with(point("zeta", 1, 0, 0.5), 8, 2)}, "z.csv");
  write_records(dir.path, {with(point("alpha", 1, 0, 0.125), 4, 0)}, "a.csv");
  std::ofstream(rundir::run_folder::records(dir.path.string()) + "/half.csv.tmp")
      << "not a records file at all\n";
  const std::string md = write_run_summary(dir.path.string());
  EXPECT_EQ(rows_of(md), (std::vector<std::string>{
                      "| alpha | point | 1 | 30 | 128x128 | 1 | 0 | 0 | 0 | 0 | 0 | PE (px) | "
                      "0.125 | 0 | 100.00% | 4.0 |",
                      "| zeta | point | 1 | 30 | 128x128 | 1 | 0 | 0 | 0 | 0 | 0 | PE (px) | 0.5 | "
                      "0 | 0.00% | 8.0 |"}));
}

// With a manifest whose last invocation ran every shard: the drawing time (the sum of render_us,
// here 1.5 s + 0.5 s), the wall time x jobs over it (10 s x 2 / 2 s = 10) and the idle
// core-seconds. An invocation that ran only some shards gives the drawing time alone.
TEST(RunSummary, TheCostParagraphComparesWallTimeWithTheDrawing) {
  testing::ScopedTempDir dir{"run_summary_cost"};
  const std::string run = dir.path.string();
  write_records(dir.path, {with(point("p1", 1, 0, 0.5), 1.5e6), with(point("p1", 1, 1, 0.5), 0.5e6)});
  rundir::RunManifest m;
  m.schema = "renderaudit-manifest";
  m.schema_version = rundir::kManifestSchemaVersion;
  m.status = "complete";
  rundir::ManifestShardCounts shards;
  shards.total = shards.complete = 4;
  m.shards = shards;
  rundir::ManifestInvocation inv;
  inv.started = "2026-11-26T05:42:52Z";
  inv.jobs = 2;
  inv.shards_to_run = 4;
  inv.elapsed_s = 10;
  inv.shard_order = "plan";
  inv.idle_core_s = 4.5;
  m.invocations = std::vector<rundir::ManifestInvocation>{inv};
  rundir::write_manifest(rundir::run_folder::manifest(run), m);
  const std::string md = write_run_summary(run);
  const std::string want =
      "\nDrawing (the sum of render_us): 2.0 s; this invocation ran every shard in 10.0 s on 2 "
      "jobs, which is 10.0 times the drivers' own drawing time (wall time x jobs over the "
      "drawing: the rest is starting workers, measuring and writing records), 4.5 core-seconds "
      "without a worker (shard order: plan).\n";
  ASSERT_GE(md.size(), want.size());
  EXPECT_EQ(md.substr(md.size() - want.size()), want) << md;

  inv.shards_to_run = 1;  // a resumed run: the wall time is not the whole run's
  m.invocations = std::vector<rundir::ManifestInvocation>{inv};
  rundir::write_manifest(rundir::run_folder::manifest(run), m);
  const std::string resumed = write_run_summary(run);
  const std::string alone = "\nDrawing (the sum of render_us): 2.0 s.\n";
  EXPECT_EQ(resumed.substr(resumed.size() - alone.size()), alone) << resumed;
}

}  // namespace
}  // namespace ra::analysis
