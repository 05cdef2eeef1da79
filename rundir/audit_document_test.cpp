// audit.json's one reader: the verdict, the counts per driver, drawing times and flakes as the
// audit writes them, and a document of another kind, version or type refused with the file and
// the key named.
#include "rundir/audit_document.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "util/errors.h"

namespace ra::rundir {
namespace {

namespace fs = std::filesystem;

// A whole audit.json with one pair; `edit` replaces its first occurrence of `from` by `to`.
std::string audit_text(const std::string& from = "", const std::string& to = "") {
  std::string t = R"({"schema": "renderaudit-audit", "schema_version": 2,
    "verdict": "FAIL", "reasons": ["2 primitives changed"],
    "baseline": {"run_dir": "/runs/base", "manifest_status": "complete"},
    "pairs": [{"baseline_platform": "q", "current_platform": "p"}],
    "counts": {"compared": 15, "changed": 2, "new_violations": 1},
    "distribution_tests": {"significant": 0, "family_size": 12},
    "views": [{"platform": "p", "baseline_platform": "q", "compared": 10, "changed": 2,
               "flakes": 1, "failed": 0},
              {"platform": "p", "baseline_platform": "q", "compared": 5, "changed": 0,
               "flakes": 0, "failed": 1}],
    "failures": {"missing_shards": [{"platform": "p"}, {"platform": "p"}],
                 "manifest": [{"platform": "p", "outcome": "recovered"}],
                 "renderer_mismatches": ["p: GL_RENDERER 'x'"]},
    "speed_measurement": {"performed": true, "warn_only": true},
    "speed": [{"baseline_platform": "q", "platform": "p", "kind": "triangle", "group": "A",
               "verdict": "slower", "ratio": 1.5, "low": 1.25, "high": 1.75},
              {"baseline_platform": "q", "platform": "p", "kind": "line", "group": "A",
               "verdict": "same", "ratio": 1.0, "low": 0.98, "high": 1.02},
              {"baseline_platform": "q", "platform": "p", "kind": "point", "group": "B",
               "verdict": "faster", "ratio": 0.5, "low": 0.25, "high": 0.75},
              {"baseline_platform": "q", "platform": "p", "kind": "point", "group": "C",
               "verdict": "unknown", "ratio": null, "low": null, "high": null}],
    "flakes": {"total": 1, "listed": 1, "items": [{"baseline_platform": "q", "platform": "p",
               "kind": "line", "view": 3, "index": 7}]}})";
  if (!from.empty()) {
    const std::size_t at = t.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) t.replace(at, from.size(), to);
  }
  return t;
}

struct AuditFolder {
  fs::path dir;
  explicit AuditFolder(const std::string& text) {
    dir = fs::temp_directory_path() /
          ("ra-audit-document-" + std::to_string(::getpid()) + "-" +
           ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream((dir / "audit.json").string()) << text;
  }
  ~AuditFolder() { fs::remove_all(dir); }
};

std::string refusal(const std::string& text) {
  const AuditFolder f(text);
  try {
    read_audit_document(f.dir.string());
  } catch (const util::UserError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(AuditDocument, ReadsTheVerdictCountsTimesAndFlakes) {
  const AuditFolder f(audit_text());
  const AuditDocument a = read_audit_document(f.dir.string());
  EXPECT_EQ(a.verdict, "FAIL");
  EXPECT_EQ(a.baseline_dir, "/runs/base");
  ASSERT_EQ(a.views.size(), 2u);
  EXPECT_EQ(a.views[0].compared, 10);
  EXPECT_EQ(a.views[0].changed, 2);
  EXPECT_EQ(a.views[0].flakes, 1);
  EXPECT_EQ(a.views[1].failed, 1);
  EXPECT_EQ(a.missing_shard_platforms.size(), 2u);
  ASSERT_EQ(a.manifest_failures.size(), 1u);
  EXPECT_EQ(a.manifest_failures[0].outcome, "recovered");
  ASSERT_EQ(a.renderer_mismatches.size(), 1u);
  ASSERT_EQ(a.reasons.size(), 1u);
  EXPECT_TRUE(a.speed_warn_only);
  EXPECT_TRUE(a.timed);
  ASSERT_EQ(a.speed.size(), 4u);
  EXPECT_DOUBLE_EQ(a.speed[0].ratio, 1.5);
  EXPECT_TRUE(std::isnan(a.speed[3].ratio));
  EXPECT_EQ(a.time_moved(), 2u);
  EXPECT_EQ(a.compared, 15u);
  EXPECT_EQ(a.changed, 2u);
  EXPECT_EQ(a.family_size, 12u);
  EXPECT_TRUE(a.compares("q", "p"));
  EXPECT_FALSE(a.compares("p", "q"));
  ASSERT_EQ(a.flakes.size(), 1u);
  EXPECT_EQ(a.flakes[0].view, 3);
  EXPECT_EQ(a.flakes[0].index, 7u);
}

TEST(AuditDocument, RefusesOtherDocumentsAndWrongTypes) {
  EXPECT_NE(refusal(audit_text("renderaudit-audit", "renderaudit-manifest"))
                .find("expected schema renderaudit-audit version 2"),
            std::string::npos);
  EXPECT_NE(refusal(audit_text("\"schema_version\": 2", "\"schema_version\": 3"))
                .find("expected schema renderaudit-audit version 2"),
            std::string::npos);
  const std::string negative = refusal(audit_text("\"compared\": 10", "\"compared\": -1"));
  EXPECT_NE(negative.find("views[0].compared' must be a whole number"), std::string::npos)
      << negative;
  const std::string list = refusal(audit_text("\"reasons\": [\"2 primitives changed\"]",
                                              "\"reasons\": [3]"));
  EXPECT_NE(list.find("'reasons' must be a list of strings"), std::string::npos) << list;
  const std::string missing = refusal(audit_text("\"verdict\": \"FAIL\",", ""));
  EXPECT_NE(missing.find("'verdict' is missing"), std::string::npos) << missing;
  const std::string cut = refusal(audit_text().substr(0, 200));
  EXPECT_NE(cut.find("audit.json: cannot read the audit"), std::string::npos) << cut;
}

}  // namespace
}  // namespace ra::rundir
