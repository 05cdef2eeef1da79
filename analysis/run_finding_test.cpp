// The line `renderaudit report` ends with (analysis/run_finding.h), on hand-built tallies.
#include "analysis/run_finding.h"

#include <gtest/gtest.h>

namespace ra::analysis {
namespace {

RunTally softpipe_tally() {
  RunTally t;
  t.records = 64000;
  auto group = [&](const char* kind, int group, std::uint64_t judged, std::uint64_t exact,
                   std::uint64_t violations, const char* label) {
    ConformanceCounts& n = t.verdicts[{"osmesa-softpipe", kind, group}];
    n.compared = judged, n.exact = exact, n.violation = violations;
    n.within_spec = judged - exact - violations;
    t.group_labels[{"osmesa-softpipe", kind, group}] = label;
  };
  group("point", 0, 40000, 40000, 0, "30 deg, 128x128");
  group("line", 1, 16000, 7000, 2, "150 deg, 128x128");
  group("triangle", 3, 8000, 7900, 0, "150 deg, 907x907");
  return t;
}

// The violations a run found are said with their counts, where they are and which file lists
// them: a user reading the terminal knows what was found without opening the report.
TEST(RunFinding, NamesTheViolationsWithTheirPlatformKindAndGroup) {
  EXPECT_EQ(run_finding_line(softpipe_tally(), "outputs/my"),
            "finding: 2 violations (GL rules broken) in 64,000 primitives: osmesa-softpipe lines "
            "2 (group B: 150 deg, 128x128); each in outputs/my/analysis/violations.md");
}

TEST(RunFinding, SaysSoWhenNoRuleIsBroken) {
  RunTally t = softpipe_tally();
  t.verdicts[{"osmesa-softpipe", "line", 1}].violation = 0;
  EXPECT_EQ(run_finding_line(t, "outputs/my"),
            "finding: no violation (no GL rule broken) in 64,000 primitives; 85.8% drawn exactly "
            "as the reference rasterizer");
}

// Records not drawn (crash, timeout) are counted beside the verdicts, never hidden by them.
TEST(RunFinding, CountsTheRecordsNotDrawn) {
  RunTally t = softpipe_tally();
  t.non_ok_counts[{"osmesa-softpipe", "line", "crash"}] = 3;
  EXPECT_NE(run_finding_line(t, "d").find("; 3 records not drawn (crash, timeout or invalid); "),
            std::string::npos)
      << run_finding_line(t, "d");
}

TEST(RunFinding, SaysWhenNothingWasJudged) {
  RunTally t;
  t.records = 500;
  EXPECT_EQ(run_finding_line(t, "d"),
            "finding: no primitive judged by GL's rules (the reference platform, or antialiased): "
            "500 records");
}

}  // namespace
}  // namespace ra::analysis
