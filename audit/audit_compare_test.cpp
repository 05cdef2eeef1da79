// Per-primitive comparison and run identity on hand-written run directories.
#include "audit/audit_compare.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "audit/audit_testing.h"
#include "audit/run_identity.h"
#include "metrics/conformance.h"
#include "util/errors.h"

namespace ra::audit {
namespace {

using testing::experiment_text;
using testing::fresh_dir;
using testing::point_record;
using testing::write_points;
using testing::write_run;

std::vector<uint64_t> changed_indices(const PrimitiveComparison& c) {
  std::vector<uint64_t> out;
  for (const auto& p : c.changed) out.push_back(p.index);
  return out;
}

// Identical records compare equal; a different pixel hash, visibility or status is a change, and
// the before/after values are those of the records.
TEST(AuditCompare, FindsExactlyThePrimitivesWhosePixelsOrClassDiffer) {
  const std::string a = fresh_dir("cmp_a"), b = fresh_dir("cmp_b");
  const std::string text = experiment_text("\"reference\"", 20, 7);
  const rundir::Experiment exp = write_run(a, text);
  write_run(b, text);
  write_points(a, exp, "reference", [&](int view, uint64_t i) {
    return point_record(exp, "reference", view, i, 1000 + i, 0.25);
  });
  write_points(b, exp, "reference", [&](int view, uint64_t i) {
    metrics::Record r = point_record(exp, "reference", view, i, 1000 + i, 0.25);
    if (i == 3 || i == 15) r.pixel_hash = 7, r.pe = 0.5;                 // other pixels
    if (i == 9)
      r.visibility = metrics::Visibility::kFalseInvisible, r.pe = metrics::kNA;  // other class
    return r;
  });
  const PrimitiveComparison c = compare_primitives(a, b, {{"reference", "reference"}}, 1);
  EXPECT_EQ(changed_indices(c), (std::vector<uint64_t>{3, 9, 15}));
  ASSERT_EQ(c.views.size(), 1u);
  EXPECT_EQ(c.views[0].compared, 20u);
  EXPECT_EQ(c.views[0].changed, 3u);
  EXPECT_EQ(c.changed[0].before.pixel_hash, 1003u);
  EXPECT_EQ(c.changed[0].after.pixel_hash, 7u);
  EXPECT_DOUBLE_EQ(c.changed[0].before.metric, 0.25);
  EXPECT_DOUBLE_EQ(c.changed[0].after.metric, 0.5);
  EXPECT_TRUE(c.failed.empty());
}

// Runs judged by different conformance rules: a class that moved with the rules is no change of
// the driver, while other pixels still are.
TEST(AuditCompare, ClassesJudgedByOtherRulesAreNotCompared) {
  const std::string a = fresh_dir("rules_a"), b = fresh_dir("rules_b");
  const std::string text = experiment_text("\"reference\"", 10, 10);
  const rundir::Experiment exp = write_run(a, text);
  write_run(b, text);
  auto judged = [&](int view, uint64_t i, metrics::Conformance c) {
    metrics::Record r = point_record(exp, "reference", view, i, 1000 + i, 0.25);
    r.conformance = c;
    r.violating_pixels = c == metrics::Conformance::kViolation ? 1 : 0;
    if (c == metrics::Conformance::kViolation) r.violated_rules = "point-missing";
    return r;
  };
  write_points(a, exp, "reference", [&](int view, uint64_t i) {
    return judged(view, i, metrics::Conformance::kWithinSpec);
  });
  write_points(b, exp, "reference", [&](int view, uint64_t i) {
    metrics::Record r = judged(
        view, i, i == 4 ? metrics::Conformance::kViolation : metrics::Conformance::kWithinSpec);
    if (i == 7) r.pixel_hash = 3;
    return r;
  });
  const std::vector<PlatformPair> pair = {{"reference", "reference"}};
  EXPECT_EQ(changed_indices(compare_primitives(a, b, pair, 1)), (std::vector<uint64_t>{4, 7}));
  EXPECT_EQ(changed_indices(compare_primitives(a, b, pair, 1, false)), (std::vector<uint64_t>{7}));
}

TEST(RunIdentity, ReadsTheConformanceRulesOfAManifestAndRefusesNonsense) {
  const std::string a = fresh_dir("rules_id");
  write_run(a, experiment_text("\"reference\"", 10, 10));
  EXPECT_EQ(load_run_identity(a).conformance_rules, 1);  // a manifest without the key
  nlohmann::json m = nlohmann::json::parse(std::ifstream(a + "/manifest.json"));
  m["conformance_rules"] = metrics::kConformanceRulesVersion;
  std::ofstream(a + "/manifest.json") << m.dump();
  EXPECT_EQ(load_run_identity(a).conformance_rules, metrics::kConformanceRulesVersion);
  m["conformance_rules"] = "two";
  std::ofstream(a + "/manifest.json") << m.dump();
  try {
    load_run_identity(a);
    FAIL() << "a non-integer conformance_rules was accepted";
  } catch (const util::UserError& e) {
    EXPECT_EQ(std::string(e.what()), a + "/manifest.json: 'conformance_rules' must be an integer "
                                         "from 1 to 1000 (found \"two\")");
  }
}

// Another shard size in one run (the [run] table is not part of the experiment) changes nothing.
TEST(AuditCompare, ShardSizesMayDiffer) {
  const std::string a = fresh_dir("shard_a"), b = fresh_dir("shard_b");
  const rundir::Experiment ea = write_run(a, experiment_text("\"reference\"", 20, 20));
  const rundir::Experiment eb = write_run(b, experiment_text("\"reference\"", 20, 3));
  ASSERT_EQ(ea.hash, eb.hash);
  for (auto [dir, exp] : {std::pair{a, &ea}, std::pair{b, &eb}})
    write_points(dir, *exp, "reference", [&](int view, uint64_t i) {
      return point_record(*exp, "reference", view, i, i, 0.1);
    });
  const PrimitiveComparison c = compare_primitives(a, b, {{"reference", "reference"}}, 2);
  EXPECT_TRUE(c.changed.empty());
  EXPECT_EQ(c.views.at(0).compared, 20u);
}

// Crash and timeout records are failures, never changes; a missing shard leaves its primitives
// unmatched and is listed, with the manifest's reason, by missing_shards().
TEST(AuditCompare, CrashTimeoutAndMissingShardsAreFailures) {
  const std::string a = fresh_dir("fail_a"), b = fresh_dir("fail_b");
  const std::string text = experiment_text("\"reference\"", 20, 5);
  const rundir::Experiment exp = write_run(a, text);
  write_run(b, text,
            nlohmann::json::array({{{"shard", "reference.point.v1.15-20"},
                                    {"reason", "crashed (signal 11, Segmentation fault)"}}}));
  write_points(a, exp, "reference", [&](int view, uint64_t i) {
    return point_record(exp, "reference", view, i, i, 0.1);
  });
  write_points(b, exp, "reference",
               [&](int view, uint64_t i) {
                 metrics::Record r = point_record(exp, "reference", view, i, i, 0.1);
                 if (i == 4) r.status = metrics::CaseStatus::kCrash, r.pixel_hash = 0;
                 if (i == 11) r.status = metrics::CaseStatus::kTimeout, r.pixel_hash = 0;
                 return r;
               },
               {"reference.point.v1.15-20"});
  const PrimitiveComparison c = compare_primitives(a, b, {{"reference", "reference"}}, 1);
  EXPECT_TRUE(c.changed.empty());
  ASSERT_EQ(c.failed.size(), 2u);
  EXPECT_EQ(c.failed[0].index, 4u);
  EXPECT_EQ(c.failed[0].status, metrics::CaseStatus::kCrash);
  EXPECT_EQ(c.failed[0].side, "current");
  EXPECT_EQ(c.failed[1].index, 11u);
  EXPECT_EQ(c.failed[1].status, metrics::CaseStatus::kTimeout);
  EXPECT_EQ(c.views.at(0).unmatched, 5u);

  const RunIdentity run = load_run_identity(b);
  const std::vector<MissingShard> missing = missing_shards(run, "reference", "current");
  ASSERT_EQ(missing.size(), 1u);
  EXPECT_EQ(missing[0].id, "reference.point.v1.15-20");
  EXPECT_EQ(missing[0].begin, 15u);
  EXPECT_EQ(missing[0].end, 20u);
  EXPECT_EQ(missing[0].reason, "crashed (signal 11, Segmentation fault)");
  const std::vector<ManifestFailure> noted = manifest_failures_of(run, "reference", "current");
  ASSERT_EQ(noted.size(), 1u);
  EXPECT_EQ(noted[0].outcome, FailureOutcome::kMissing);
  EXPECT_EQ(noted[0].begin, 15u);
  EXPECT_TRUE(manifest_failures_of(run, "osmesa-llvmpipe", "current").empty());
}

// Two platforms of one run: P1 plays the baseline.
TEST(AuditCompare, BetweenTwoPlatformsOfOneRun) {
  const std::string a = fresh_dir("between");
  const rundir::Experiment exp = write_run(a, experiment_text("\"reference\", \"faulty\"", 10, 10));
  write_points(a, exp, "reference", [&](int view, uint64_t i) {
    return point_record(exp, "reference", view, i, i, 0.1);
  });
  write_points(a, exp, "faulty", [&](int view, uint64_t i) {
    return point_record(exp, "faulty", view, i, i == 6 ? 99 : i, 0.1);
  });
  const PrimitiveComparison c = compare_primitives(a, a, {{"reference", "faulty"}}, 1);
  EXPECT_EQ(changed_indices(c), (std::vector<uint64_t>{6}));
  EXPECT_EQ((PlatformPair{"reference", "faulty"}.label()), "reference vs faulty");
  EXPECT_EQ((PlatformPair{"faulty", "faulty"}.label()), "faulty");
}

// Runs of different experiments are refused with both hashes and seeds in the message.
TEST(RunIdentity, RefusesDifferentExperimentsNamingBothHashes) {
  const std::string a = fresh_dir("id_a"), b = fresh_dir("id_b");
  const rundir::Experiment ea = write_run(a, experiment_text("\"reference\"", 10, 10, 1));
  const rundir::Experiment eb = write_run(b, experiment_text("\"reference\"", 10, 10, 2));
  const RunIdentity ra = load_run_identity(a), rb = load_run_identity(b);
  EXPECT_EQ(ra.drivers.at("reference").renderer, "reference renderer");
  EXPECT_EQ(driver_of(ra, "osmesa-softpipe").renderer, "unknown");
  std::string message;
  try {
    require_same_experiment(ra, rb);
  } catch (const util::UserError& e) {
    message = e.what();
  }
  EXPECT_NE(message.find(ea.hash), std::string::npos) << message;
  EXPECT_NE(message.find(eb.hash), std::string::npos) << message;
  EXPECT_NE(message.find("seed 1"), std::string::npos) << message;
  EXPECT_NE(message.find("seed 2"), std::string::npos) << message;
  EXPECT_NO_THROW(require_same_experiment(ra, ra));
  EXPECT_THROW(load_run_identity(a + "/records"), util::UserError);  // not a run directory
}

}  // namespace
}  // namespace ra::audit
