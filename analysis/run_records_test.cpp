// Tests of loading a run directory: counts per visibility class and status, metric samples (only
// true-visible `ok` values, sorted), view groups, and located errors for bad input.
#include "analysis/run_records.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "analysis/records_testing.h"
#include "util/errors.h"
#include "tests/cli_harness.h"

namespace ra::analysis {
namespace {

using testing::point;
using testing::write_records;

// The message of the UserError that `f` throws ("" when it throws none).
template <typename F>
std::string user_error(F f) {
  return ra::testing_cli::error_message<util::UserError>(f);
}

TEST(RunRecords, CountsSamplesAndGroups) {
  const testing::ScopedTempDir scoped("records_counts");
  const std::filesystem::path& dir = scoped.path;
  std::vector<metrics::Record> rs = {
      point("p1", 1, 0, 0.30),
      point("p1", 1, 1, 0.10),
      point("p1", 1, 2, 0, metrics::Visibility::kTrueInvisible),
      point("p1", 1, 3, 0, metrics::Visibility::kFalseVisible),
      point("p1", 1, 4, 0, metrics::Visibility::kFalseInvisible),
      point("p1", 1, 5, 0, metrics::Visibility::kMultipleVisible),
      point("p1", 1, 6, 0.7, metrics::Visibility::kTrueVisible, metrics::CaseStatus::kInvalid),
      point("p1", 1, 7, 0.7, metrics::Visibility::kTrueVisible, metrics::CaseStatus::kCrash),
      point("p1", 2, 0, 0.25),
      point("p1", 3, 0, 0, metrics::Visibility::kTrueInvisible),
  };
  write_records(dir, rs, "a.csv");
  write_records(dir, {point("p0", 2, 0, 0.5), testing::unmeasured_line("p1", 1, 0)}, "b.csv");
  std::ofstream(dir / "records" / "c.csv.tmp") << "unfinished shard, ignored";

  const RunRecords run = load_run_records(dir.string());
  EXPECT_EQ(run.files.size(), 2u);
  EXPECT_EQ(run.record_count, rs.size() + 2);
  ASSERT_EQ(run.platforms, (std::vector<std::string>{"p0", "p1"}));  // sorted by name

  const ViewData& v1 = run.views.at(ViewKey{1, geometry::Kind::kPoint, 1});
  EXPECT_EQ(v1.counts.by_class, (std::array<std::uint64_t, 5>{2, 1, 1, 1, 1}));
  EXPECT_EQ(v1.counts.invalid, 1u);
  EXPECT_EQ(v1.counts.crash, 1u);
  EXPECT_EQ(v1.counts.timeout, 0u);
  EXPECT_EQ(v1.values[metric_index(geometry::Kind::kPoint, "pe")],
            (std::vector<double>{0.10, 0.30}));
  EXPECT_EQ(v1.values[metric_index(geometry::Kind::kPoint, "pe_norm")],
            (std::vector<double>{0.10 / 128, 0.30 / 128}));
  EXPECT_EQ(v1.render_us_visible.size(), 2u);
  EXPECT_EQ(v1.render_us_other.size(), 4u);  // the ok records that are not true-visible
  EXPECT_EQ(v1.meta.fov_deg, 30);
  EXPECT_EQ(v1.meta.width, 128);

  // group A of p1 pools views 1 and 2, ascending
  const ViewGroup* a = run.find_group(1, geometry::Kind::kPoint, 0);
  ASSERT_NE(a, nullptr);
  EXPECT_EQ(a->label, "A");
  EXPECT_EQ(a->view_numbers(), (std::vector<int>{1, 2}));
  EXPECT_EQ(a->pooled(0), (std::vector<double>{0.10, 0.25, 0.30}));
  EXPECT_EQ(a->counts().by_class[0], 3u);
  const ViewGroup* b = run.find_group(1, geometry::Kind::kPoint, 1);
  ASSERT_NE(b, nullptr);
  EXPECT_EQ(b->count(0), 0u);

  // a line whose metric cells are empty: counted as true-visible, values missing, no NaN
  const ViewData& line = run.views.at(ViewKey{1, geometry::Kind::kLine, 1});
  EXPECT_EQ(line.counts.by_class[0], 1u);
  for (std::size_t m = 0; m < line.values.size(); ++m) {
    EXPECT_TRUE(line.values[m].empty());
    EXPECT_EQ(line.missing[m], 1u);
  }
  EXPECT_EQ(run.kinds(),
            (std::vector<geometry::Kind>{geometry::Kind::kPoint, geometry::Kind::kLine}));
  EXPECT_EQ(view_group_label(27), "AB");
}

TEST(RunRecords, MissingDirectoryOrRecordsAreUserErrors) {
  const testing::ScopedTempDir scoped("records_missing");
  const std::filesystem::path& dir = scoped.path;
  EXPECT_NE(user_error([&] {
              load_run_records((dir / "nope").string());
            }).find((dir / "nope").string() + ": no such directory"),
            std::string::npos);
  EXPECT_NE(user_error([&] { load_run_records(dir.string()); }).find("no records directory"),
            std::string::npos);
  std::filesystem::create_directories(dir / "records");
  EXPECT_NE(user_error([&] { load_run_records(dir.string()); }).find("no records files"),
            std::string::npos);
}

TEST(RunRecords, MalformedRecordsNameFileAndLine) {
  const testing::ScopedTempDir scoped("records_malformed");
  const std::filesystem::path& dir = scoped.path;
  const std::string path = write_records(dir, {point("p", 1, 0, 0.3), point("p", 1, 1, 0.2)});
  const std::string good = testing::read_text(path);

  const auto with = [&](const std::string& text) {
    std::ofstream(path) << text;
    return user_error([&] { load_run_records(dir.string()); });
  };
  // a missing field on line 3
  std::string text = good;
  text.erase(text.rfind(','), 1);
  std::string e = with(text);
  EXPECT_NE(e.find(path + ":3: expected 39 fields, found 38"), std::string::npos) << e;
  // a value that is not a number
  text = good;
  const std::size_t at = text.find(",0.3,");  // pe, written shortest round-trip
  ASSERT_NE(at, std::string::npos) << text;
  text.replace(at, 5, ",abc,");
  e = with(text);
  EXPECT_NE(e.find(path + ":2: column 'pe': 'abc' is not a finite number"), std::string::npos) << e;
  // nan is not accepted either
  text = good;
  text.replace(at, 5, ",nan,");
  EXPECT_NE(with(text).find(":2: column 'pe': 'nan' is not a finite number"), std::string::npos);
  // unknown visibility
  text = good;
  text.replace(text.find("true-visible"), 12, "very-visible");
  EXPECT_NE(with(text).find(path + ":2: unknown visibility 'very-visible'"), std::string::npos);
  // another header (schema change)
  e = with("platform,view\n");
  EXPECT_NE(e.find(path + ":1: unexpected records header"), std::string::npos) << e;
  e = with("");
  EXPECT_NE(e.find(path + ":1: unexpected records header"), std::string::npos) << e;
}

TEST(RunRecords, InconsistentViewsAndDuplicatesAreRefused) {
  const testing::ScopedTempDir scoped("records_inconsistent");
  const std::filesystem::path& dir = scoped.path;
  metrics::Record changed = point("p", 1, 1, 0.2);
  changed.fov_deg = 45;
  const std::string path = write_records(dir, {point("p", 1, 0, 0.3), changed});
  std::string e = user_error([&] { load_run_records(dir.string()); });
  EXPECT_NE(e.find(path + ":3: view 1 (p, point) has fov_deg 45 here but 30 on line 2"),
            std::string::npos)
      << e;

  // the same records in two files: counted twice otherwise
  write_records(dir, {point("p", 1, 0, 0.3), point("p", 1, 1, 0.2)}, "x.csv");
  write_records(dir, {point("p", 1, 1, 0.2)}, "y.csv");
  e = user_error([&] { load_run_records(dir.string()); });
  EXPECT_NE(e.find("index 1 appear more than once"), std::string::npos) << e;
  EXPECT_NE(e.find("x.csv"), std::string::npos) << e;
  EXPECT_NE(e.find("y.csv"), std::string::npos) << e;
}

TEST(RunRecords, MergeAndDescribeSorted) {
  const std::vector<double> a = {1, 3, 5}, b = {2, 4}, c = {};
  EXPECT_EQ(merge_sorted({&a, &b, &c}), (std::vector<double>{1, 2, 3, 4, 5}));
  const stats::Description d =
      describe_sorted({0.05, 0.10, 0.20, 0.25, 0.30, 0.40, 0.45, 0.50, 0.60},
                      stats::QuantileDefinition::kHyndmanFan6);
  EXPECT_DOUBLE_EQ(d.median, 0.30);
  EXPECT_DOUBLE_EQ(d.q1, 0.15);
  EXPECT_DOUBLE_EQ(d.q3, 0.475);
  EXPECT_THROW(describe_sorted({2, 1}, stats::QuantileDefinition::kHyndmanFan6), std::logic_error);
}

// The conformance verdicts are tallied in the pass that loads the records, file by file and joined
// in file order: counts summed over files, each group's label from its first record, the first 30
// records that are not `ok` by file then line, violations worst first across files. Counted here
// by hand.
TEST(RunRecords, TalliesTheVerdictsOfEveryFileInFileOrder) {
  const testing::ScopedTempDir scoped("records_verdicts");
  const std::filesystem::path& dir = scoped.path;
  auto judged = [](int view, std::uint64_t index, metrics::Conformance c, std::int64_t pixels,
                   const char* rules) {
    metrics::Record r = point("p1", view, index, 0.2);
    r.conformance = c;
    r.violating_pixels = pixels;
    r.violated_rules = rules;
    r.ref_diff = c == metrics::Conformance::kExact ? 0 : 1;
    return r;
  };
  std::vector<metrics::Record> a, b;
  for (std::uint64_t i = 0; i < 20; ++i)
    a.push_back(point("p1", 1, 100 + i, 0, metrics::Visibility::kTrueVisible, metrics::CaseStatus::kCrash));
  a.push_back(judged(1, 0, metrics::Conformance::kExact, 0, ""));
  a.push_back(judged(1, 1, metrics::Conformance::kViolation, 2, "point-pixel"));
  for (std::uint64_t i = 0; i < 20; ++i)
    b.push_back(point("p1", 2, 100 + i, 0, metrics::Visibility::kTrueVisible, metrics::CaseStatus::kTimeout));
  b.push_back(judged(2, 0, metrics::Conformance::kViolation, 9, "point-pixel"));
  b.push_back(judged(2, 1, metrics::Conformance::kWithinSpec, 0, ""));
  write_records(dir, a, "a.csv");
  write_records(dir, b, "b.csv");

  const ConformanceSummary& s = load_run_records(dir.string()).conformance;
  const GroupKey group{"p1", "point", 0};
  ASSERT_EQ(s.groups.size(), 1u);
  const ConformanceCounts& n = s.groups.at(group);
  EXPECT_EQ(n.compared, 4u);
  EXPECT_EQ(n.exact, 1u);
  EXPECT_EQ(n.within_spec, 1u);
  EXPECT_EQ(n.violation, 2u);
  EXPECT_EQ(n.violating_pixels, 11u);
  EXPECT_EQ(n.rules.at("point-pixel"), 2u);
  ASSERT_EQ(s.violations.size(), 2u);  // the worse one (9 px, second file) first
  EXPECT_EQ(s.violations[0].view, 2);
  EXPECT_EQ(s.violations[1].view, 1);
  EXPECT_EQ(s.reference.at(group).compared, 4u);
  EXPECT_EQ(s.reference.at(group).identical, 1u);
  EXPECT_EQ(s.group_labels.at(group), "30 deg, 128x128");
  EXPECT_EQ(s.non_ok_counts.at({"p1", "point", "crash"}), 20u);
  EXPECT_EQ(s.non_ok_counts.at({"p1", "point", "timeout"}), 20u);
  ASSERT_EQ(s.non_ok_examples.size(), kNonOkExamples);  // 30 of the 40
  EXPECT_EQ(s.non_ok_examples[0].file, "records/a.csv");
  EXPECT_EQ(s.non_ok_examples[0].line, 2u);
  EXPECT_EQ(s.non_ok_examples[19].index, 119u);
  EXPECT_EQ(s.non_ok_examples[20].file, "records/b.csv");
  EXPECT_EQ(s.non_ok_examples[20].status, "timeout");
  EXPECT_EQ(s.non_ok_examples[29].index, 109u);
  // the same as the summary read straight from the files
  const ConformanceSummary direct = summarize_conformance(
      {(dir / "records" / "a.csv").string(), (dir / "records" / "b.csv").string()}, dir.string());
  EXPECT_EQ(direct.non_ok_examples.size(), s.non_ok_examples.size());
  EXPECT_EQ(direct.non_ok_examples.back().file, s.non_ok_examples.back().file);
  EXPECT_EQ(direct.violations[0].index, s.violations[0].index);
}

// merge_sorted against sorting the concatenation, for 0 to 9 parts (empty ones among them) of
// random lengths and values with ties.
TEST(RunRecords, MergeSortedEqualsSortingEveryPart) {
  std::uint64_t state = 7;
  const auto next = [&state] {  // a 64-bit LCG (Knuth's MMIX constants), upper bits
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return state >> 33;
  };
  for (std::size_t k = 0; k <= 9; ++k) {
    std::vector<std::vector<double>> parts(k);
    std::vector<const std::vector<double>*> pointers;
    std::vector<double> want;
    for (auto& p : parts) {
      p.resize(next() % 50 * (next() % 4 != 0));  // a quarter of them empty
      for (double& x : p) x = double(next() % 40) / 4;
      std::sort(p.begin(), p.end());
      want.insert(want.end(), p.begin(), p.end());
      pointers.push_back(&p);
    }
    std::sort(want.begin(), want.end());
    EXPECT_EQ(merge_sorted(pointers), want) << k << " parts";
  }
}

}  // namespace
}  // namespace ra::analysis
