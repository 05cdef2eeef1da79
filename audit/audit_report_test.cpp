// The verdict rule (audit/audit.h) and the writers (audit/audit_report.h) on hand-built results.
#include "audit/audit_report.h"

#include <gtest/gtest.h>

namespace ra::audit {
namespace {

AuditResult result_with(std::vector<Recheck> changes) {
  AuditResult r;
  r.mode = "runs";
  r.date_utc = "2026-01-01T03:00:00Z";
  r.baseline.dir = "outputs/base";
  r.current.dir = "outputs/cur rent";  // a space: the show line must quote it
  r.current.name = "nightly";
  r.current.hash = "0123456789abcdef";
  r.pairs = {{"osmesa-llvmpipe", "osmesa-llvmpipe"}};
  r.baseline_drivers = {{"osmesa-llvmpipe", "llvmpipe (LLVM 15)", "Mesa 22.3.6"}};
  r.current_drivers = {{"osmesa-llvmpipe", "llvmpipe (LLVM 16)", "Mesa 23.0.0"}};
  r.primitives.views = {{0, geometry::Kind::kLine, 1, 0, 100, uint64_t(changes.size()), 0, 0},
                        {0, geometry::Kind::kLine, 2, 0, 100, 0, 0, 0}};
  uint64_t index = 10;
  for (Recheck c : changes) {
    ChangedPrimitive p;
    p.kind = geometry::Kind::kLine, p.view = 1, p.index = index++;
    p.before.pixel_hash = 1, p.after.pixel_hash = 2, p.before.pixels = 5, p.after.pixels = 6;
    p.before.metric = 0.25, p.after.metric = 0.5;
    p.recheck = c;
    r.primitives.changed.push_back(p);
  }
  r.flakes.performed = true;
  r.flakes.cap = 2000;
  return r;
}

TEST(AuditVerdict, NothingChangedIsUnchanged) {
  AuditResult r = result_with({});
  decide_verdict(r);
  EXPECT_EQ(r.verdict, Verdict::kUnchanged);
}

// Flakes alone leave the verdict unchanged and are counted apart.
TEST(AuditVerdict, FlakesAreNotChanges) {
  AuditResult r = result_with({Recheck::kFlake, Recheck::kFlake});
  decide_verdict(r);
  EXPECT_EQ(r.verdict, Verdict::kUnchanged);
  EXPECT_EQ(r.flake_count(), 2u);
  EXPECT_EQ(r.changed_count(), 0u);
  EXPECT_NE(r.reasons.at(0).find("flakes"), std::string::npos) << r.reasons[0];
}

// A persisting difference, or one never re-rendered (over the cap), is a change.
TEST(AuditVerdict, PersistingOrUncheckedDifferencesAreChanges) {
  AuditResult r = result_with({Recheck::kFlake, Recheck::kStillDifferent});
  decide_verdict(r);
  EXPECT_EQ(r.verdict, Verdict::kChanged);
  AuditResult capped = result_with({Recheck::kNotRerendered});
  decide_verdict(capped);
  EXPECT_EQ(capped.verdict, Verdict::kChanged);
}

// Failures win over changes: crash records, missing shards, renderer mismatches.
TEST(AuditVerdict, FailuresWin) {
  AuditResult crash = result_with({Recheck::kStillDifferent});
  crash.primitives.failed.push_back({0, "current", "osmesa-llvmpipe", geometry::Kind::kLine, 2, 0,
                                     7, metrics::CaseStatus::kCrash});
  decide_verdict(crash);
  EXPECT_EQ(crash.verdict, Verdict::kFailed);
  AuditResult missing = result_with({});
  missing.missing.push_back({"current", "osmesa-llvmpipe", geometry::Kind::kLine, 1, 0, 0, 10,
                             "osmesa-llvmpipe.line.v1.0-10", "no records file"});
  decide_verdict(missing);
  EXPECT_EQ(missing.verdict, Verdict::kFailed);
  AuditResult driver = result_with({});
  driver.renderer_mismatches.push_back("osmesa-llvmpipe: GL_RENDERER 'x' does not match");
  decide_verdict(driver);
  EXPECT_EQ(driver.verdict, Verdict::kFailed);
  EXPECT_EQ(driver.reasons.at(0), driver.renderer_mismatches[0]);
}

TEST(AuditReport, MarkdownLeadsWithTheVerdictAndListsShowLines) {
  AuditResult r = result_with({Recheck::kStillDifferent, Recheck::kFlake});
  decide_verdict(r);
  const std::string md = audit_markdown(r);
  EXPECT_EQ(md.rfind("# renderaudit audit: CHANGED\n\n**Verdict: changed** (exit code 1)", 0), 0u)
      << md;
  EXPECT_NE(md.find("| osmesa-llvmpipe | llvmpipe (LLVM 15) | Mesa 22.3.6 | llvmpipe (LLVM 16) | "
                    "Mesa 23.0.0 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("`renderaudit show 'outputs/cur rent' --platform osmesa-llvmpipe --kind line "
                    "--view 1 --index 10`"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("lse_u 0.25 -> 0.5"), std::string::npos) << md;
  EXPECT_NE(md.find("## Flakes"), std::string::npos);
  EXPECT_NE(md.find("index 11"), std::string::npos);  // the flake, listed under Flakes
}

// Two testcases per kind x view group (the pixels, the conformance verdicts) + drivers, shards;
// a failure element when changed.
TEST(AuditReport, JunitHasOneCasePerGroup) {
  AuditResult r = result_with({Recheck::kStillDifferent});
  decide_verdict(r);
  const std::string xml = audit_junit(r);
  EXPECT_NE(xml.find("<testsuites name=\"renderaudit audit\" tests=\"4\" failures=\"1\""),
            std::string::npos)
      << xml;
  EXPECT_NE(xml.find("name=\"group A (views 1, 2)\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("<failure type=\"changed\" message=\"1 primitive(s) changed"),
            std::string::npos)
      << xml;
  EXPECT_NE(xml.find("classname=\"renderaudit.audit.osmesa-llvmpipe.line\""), std::string::npos);
}

std::size_t occurrences(const std::string& text, const std::string& word) {
  std::size_t n = 0;
  for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) ++n;
  return n;
}

// A run audited against itself (the first night of a series) compares nothing, so no line of its
// audit.md reads as a comparison, and every JUnit case is skipped: none was judged.
TEST(AuditReport, ABaselineNightReadsAsNoComparison) {
  AuditResult r = result_with({});
  r.verdict = Verdict::kBaseline;  // decide_verdict says so for one directory on both sides
  r.reasons = {"the baseline and the current run are one directory"};
  r.distributions.family_size = 152;
  const std::string md = audit_markdown(r);
  EXPECT_EQ(md.rfind("# renderaudit audit: BASELINE ESTABLISHED: NOTHING COMPARED\n", 0), 0u) << md;
  EXPECT_EQ(occurrences(md, "compared"), occurrences(md, "nothing compared")) << md;
  for (const char* comparison : {"unchanged", "No test is significant", "same on both sides",
                                 "New conformance violations", "Changed primitives", "Flakes"})
    EXPECT_EQ(md.find(comparison), std::string::npos) << comparison << "\n" << md;
  EXPECT_NE(md.find("| osmesa-llvmpipe | line | A | 1, 2 | 200 | baseline recorded |"),
            std::string::npos)
      << md;

  const std::string xml = audit_junit(r);
  EXPECT_EQ(occurrences(xml, "<testcase "), 4u) << xml;  // drivers, shards, group A, conformance
  EXPECT_EQ(occurrences(xml, "<skipped message=\"baseline established: nothing compared\"/>"), 4u)
      << xml;
  EXPECT_EQ(xml.find("name=\"compared\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("<property name=\"primitives\" value=\"200\"/>"), std::string::npos) << xml;
}

// A primitive that now breaks a GL rule (and did not in the baseline) comes first in audit.md and
// fails the group's conformance testcase; one that already broke it in the baseline does not.
TEST(AuditReport, NewViolationsComeFirstAndFailTheirConformanceCase) {
  AuditResult r = result_with({Recheck::kStillDifferent, Recheck::kStillDifferent});
  r.primitives.changed[0].before.conformance = metrics::Conformance::kWithinSpec;
  r.primitives.changed[0].after.conformance = metrics::Conformance::kViolation;
  r.primitives.changed[0].after.violating_pixels = 3;
  r.primitives.changed[1].before.conformance = metrics::Conformance::kViolation;
  r.primitives.changed[1].after.conformance = metrics::Conformance::kViolation;
  decide_verdict(r);
  const std::vector<GroupOutcome> g = group_outcomes(r);
  ASSERT_EQ(g.size(), 1u);
  EXPECT_EQ(g[0].new_violations, 1u);
  const std::string md = audit_markdown(r);
  const std::size_t first = md.find("## New conformance violations");
  ASSERT_NE(first, std::string::npos);
  EXPECT_LT(first, md.find("## Drivers"));
  EXPECT_NE(md.find("index 10: within-spec -> violation (3 px)"), std::string::npos) << md;
  EXPECT_EQ(md.find("index 11: violation"), std::string::npos) << md;
  EXPECT_NE(md.find("1 primitives break a GL rasterization rule"), std::string::npos) << md;
  const std::string xml = audit_junit(r);
  EXPECT_NE(xml.find("tests=\"4\" failures=\"2\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("name=\"conformance, group A (views 1, 2)\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("<failure type=\"violation\" message=\"1 primitive(s) break a GL "
                     "rasterization rule the baseline did not break\">line view 1 index 10: 3 "
                     "violating pixel(s)"),
            std::string::npos)
      << xml;
}

// A change of class alone (same pixels, a new effective grid) is a change; a baseline without
// verdicts (schema version 2) is not.
TEST(AuditCompare, AChangeOfClassIsAChangeWhenBothSidesHaveOne) {
  PrimitiveState a, b;
  a.pixel_hash = b.pixel_hash = 7;
  a.conformance = metrics::Conformance::kExact;
  b.conformance = metrics::Conformance::kSnapped;
  EXPECT_TRUE(states_differ(a, b));
  a.conformance = metrics::Conformance::kNotCompared;
  EXPECT_FALSE(states_differ(a, b));
}

TEST(AuditReport, JsonCarriesSchemaVersionAndLists) {
  AuditResult r = result_with({Recheck::kStillDifferent, Recheck::kFlake});
  decide_verdict(r);
  const nlohmann::json j = audit_json(r);
  EXPECT_EQ(j["schema_version"], 2);
  EXPECT_EQ(j["verdict"], "changed");
  EXPECT_EQ(j["exit_code"], 1);
  EXPECT_EQ(j["changed_primitives"]["total"], 1);
  EXPECT_EQ(j["changed_primitives"]["items"][0]["index"], 10);
  EXPECT_EQ(j["changed_primitives"]["items"][0]["before"]["pixel_hash"], "1");
  EXPECT_EQ(j["flakes"]["items"][0]["index"], 11);
  EXPECT_EQ(j["views"][0]["changed"], 1);  // flakes apart
  EXPECT_EQ(j["views"][0]["flakes"], 1);
  const std::string csv = changed_primitives_csv(r);
  EXPECT_NE(csv.find("\nosmesa-llvmpipe,osmesa-llvmpipe,line,1,0,10,still different,"),
            std::string::npos)
      << csv;
}

}  // namespace
}  // namespace ra::audit
