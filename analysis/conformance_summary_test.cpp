// The conformance summary of records with known verdicts: counts per platform x kind x group,
// shares with Clopper-Pearson intervals (SciPy's, to the printed digits), violations worst first
// with their show lines, and records without a verdict left out.
#include "analysis/conformance_summary.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "metrics/records.h"

namespace ra::analysis {
namespace {

TEST(ConformanceSummary, CountsSharesAndTheWorstViolationsFirst) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("ra_conformance_" + std::to_string(::getpid()) + ".csv")).string();
  {
    std::ofstream out(path);
    out << metrics::records_header() << '\n';
    auto row = [&](const char* platform, const char* kind, int view, int group, uint64_t index,
                   metrics::Conformance c, int64_t pixels, const char* rules) {
      metrics::Record r;
      r.platform = platform, r.kind = kind, r.view = view, r.view_group = group, r.index = index;
      r.conformance = c;
      r.violating_pixels = c == metrics::Conformance::kNotCompared ? -1 : pixels;
      r.violated_rules = rules;
      write_record(out, r);
    };
    for (uint64_t i = 0; i < 90; ++i)
      row("soft", "line", 1, 0, i, metrics::Conformance::kExact, 0, "");
    for (uint64_t i = 90; i < 97; ++i)
      row("soft", "line", 1, 0, i, metrics::Conformance::kWithinSpec, 0, "");
    row("soft", "line", 2, 0, 97, metrics::Conformance::kViolation, 1, "line-column");
    row("soft", "line", 2, 0, 98, metrics::Conformance::kViolation, 3, "line-deviation+line-count");
    row("soft", "line", 2, 0, 99, metrics::Conformance::kSnapped, 0, "");
    row("soft", "triangle", 5, 2, 7, metrics::Conformance::kViolation, 301, "polygon-edge");
    row("reference", "line", 1, 0, 0, metrics::Conformance::kNotCompared, 0, "");
  }
  const ConformanceSummary s = summarize_conformance({path});
  std::filesystem::remove(path);
  ASSERT_EQ(s.groups.size(), 2u);
  const ConformanceCounts& lines = s.groups.at({"soft", "line", 0});
  EXPECT_EQ(lines.compared, 100u);
  EXPECT_EQ(lines.exact, 90u);
  EXPECT_EQ(lines.snapped, 1u);
  EXPECT_EQ(lines.within_spec, 7u);
  EXPECT_EQ(lines.violation, 2u);
  EXPECT_EQ(lines.violating_pixels, 4u);
  EXPECT_EQ(lines.rules.at("line-count"), 1u);
  EXPECT_EQ(lines.rules.at("line-column"), 1u);
  EXPECT_EQ(s.not_compared, 1u);
  ASSERT_EQ(s.violations.size(), 3u);
  EXPECT_EQ(s.violations[0].violating_pixels, 301);
  EXPECT_EQ(s.violations[1].index, 98u);
  EXPECT_EQ(s.violations[2].index, 97u);

  const std::string md = stats::render_markdown(conformance_table(s));
  // 97 of 100 exact-or-better shares: 90% exact, Clopper-Pearson 95% (82.38-95.10), SciPy 1.10.
  EXPECT_NE(md.find("| soft | line | A | 100 | 90.00 (82.38-95.10) | 1.00 (0.03-5.45) | 7.00 "
                    "(2.86-13.89) | 2.00 (0.24-7.04) | 4 | line-column 1, line-count 1, "
                    "line-deviation 1 |"),
            std::string::npos)
      << md;
  const std::string list = violations_markdown(s, "runs/x");
  EXPECT_NE(list.find("3 records break a GL rasterization rule"), std::string::npos) << list;
  EXPECT_NE(list.find("| soft | triangle | 5 | 7 | 301 | polygon-edge | `renderaudit show runs/x "
                      "-p soft -k triangle -v 5 -i 7` |"),
            std::string::npos)
      << list;
}

}  // namespace
}  // namespace ra::analysis
