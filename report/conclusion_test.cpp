// The report's conclusion counts what `analyze` counted: on a small synthetic run analysed by
// analyze_run, analysis/tally.json equals the counts the records were built with, and its
// sentence and findings row carry exactly those numbers (read back from the file).
#include "report/conclusion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

#include "analysis/records_testing.h"
#include "analysis/run_analysis.h"
#include "analysis/run_tally.h"
#include "report/html_writer.h"
#include "report/pdf_writer.h"
#include "tests/cli_harness.h"

namespace ra::report {
namespace {

namespace an = ra::analysis;

// Platform "soft", points, view group A (views 1 and 2), rows 2.. of records/x.csv in this order:
// indices 0-9 lit and exact (ref_diff 0), 10-12 within-spec (ref_diff 2), 13 a violation of one
// pixel, 14-15 invisible and exact (nothing lit: compared, not drawn), 16 invalid, 17 crash; then
// platform "ref" (the reference: ref_diff 0, no verdict), indices 0-3.
std::vector<metrics::Record> verdict_run() {
  std::vector<metrics::Record> rs;
  for (std::uint64_t i = 0; i < 18; ++i) {
    const bool visible = i < 14;
    const metrics::CaseStatus status = i == 16   ? metrics::CaseStatus::kInvalid
                                       : i == 17 ? metrics::CaseStatus::kCrash
                                                 : metrics::CaseStatus::kOk;
    metrics::Record r = an::testing::point(
        "soft", 1 + int(i % 2), i, 0.25,
        visible ? metrics::Visibility::kTrueVisible : metrics::Visibility::kTrueInvisible, status);
    if (status != metrics::CaseStatus::kOk) {
      rs.push_back(r);
      continue;
    }
    r.ref_diff = i >= 10 && i <= 12 ? 2 : i == 13 ? 1 : 0;
    r.conformance = i >= 10 && i <= 12 ? metrics::Conformance::kWithinSpec
                    : i == 13          ? metrics::Conformance::kViolation
                                       : metrics::Conformance::kExact;
    r.violating_pixels = i == 13 ? 1 : 0;
    r.violated_rules = i == 13 ? "point-position" : "";
    rs.push_back(r);
  }
  for (std::uint64_t i = 0; i < 4; ++i) {
    metrics::Record r = an::testing::point("ref", 1 + int(i % 2), i, 0.0);
    r.ref_diff = 0;
    rs.push_back(r);
  }
  return rs;
}

std::string all_text(const std::vector<Block>& blocks) {
  std::string text;
  for (const Block& b : blocks) {
    text += b.text + "\n";
    for (const auto& item : b.items) text += item + "\n";
    for (const auto& row : b.table.rows) {
      for (const auto& cell : row) text += cell + "|";
      text += "\n";
    }
  }
  return text;
}

// Why: plot and report no longer read the records; what they show must be what analyze counted,
// and that must be what the records hold.
TEST(Conclusion, NumbersAreTheAnalysisTallyOfTheRecords) {
  const an::testing::ScopedTempDir scoped("conclusion_tally");
  const std::string dir = scoped.path.string();
  an::testing::write_records(scoped.path, verdict_run());
  an::AnalyzeOptions o;
  o.run_dir = dir;
  an::analyze_run(o);

  const an::RunTally t = an::read_tally(dir);
  EXPECT_EQ(t.records, 22u);
  EXPECT_EQ(t.files, 1u);
  const an::GroupKey soft{"soft", "point", 0}, ref{"ref", "point", 0};
  const an::ReferenceAgreement& a = t.reference.at(soft);
  EXPECT_EQ(a.compared, 16u);
  EXPECT_EQ(a.identical, 12u);
  EXPECT_EQ(a.drawn, 14u);  // lit, or ref_diff > 0: indices 0-13
  EXPECT_EQ(a.drawn_identical, 10u);
  EXPECT_EQ(t.reference.at(ref).compared, 4u);
  const an::ConformanceCounts& v = t.verdicts.at(soft);
  EXPECT_EQ(v.compared, 16u);
  EXPECT_EQ(v.exact, 12u);
  EXPECT_EQ(v.snapped, 0u);
  EXPECT_EQ(v.within_spec, 3u);
  EXPECT_EQ(v.violation, 1u);
  EXPECT_EQ(v.violating_pixels, 1u);
  EXPECT_EQ(t.verdicts.count(ref), 0u);  // the reference has no verdict
  EXPECT_EQ(t.group_labels.at(soft), "30 deg, 128x128");
  EXPECT_EQ((t.non_ok_counts.at({"soft", "point", "invalid"})), 1u);
  EXPECT_EQ((t.non_ok_counts.at({"soft", "point", "crash"})), 1u);
  ASSERT_EQ(t.non_ok_examples.size(), 2u);
  EXPECT_EQ(t.non_ok_examples[0].file, "records/x.csv");
  EXPECT_EQ(t.non_ok_examples[0].line, 18u);  // the header is line 1, index 16 line 18
  EXPECT_EQ(t.non_ok_examples[0].index, 16u);
  EXPECT_EQ(t.non_ok_examples[1].status, "crash");
  // render_us = 10 + index % 7 over indices 0-15: sorted 10 10 10 11 11 11 12 12 13 13 14 14 15
  // 15 16 16, median 12.5; Hyndman-Fan 6 quartiles at positions 4.25 and 12.75: 11 and 14.75.
  // True-visible, indices 0-13: 10 10 11 11 ... 16 16, median 13.
  const an::RenderTime& rt = t.render_time.at({"soft", "point"});
  EXPECT_EQ(rt.cases, 16u);
  EXPECT_DOUBLE_EQ(rt.median_us, 12.5);
  EXPECT_DOUBLE_EQ(rt.iqr_us, 3.75);
  EXPECT_EQ(rt.true_visible, 14u);
  ASSERT_TRUE(rt.median_us_true_visible);
  EXPECT_DOUBLE_EQ(*rt.median_us_true_visible, 13);

  // The conclusion says the file's numbers: 12 of 16 exact (75.00%), 3 other (18.75%), 1 violation.
  const std::string text = all_text(conclusion_blocks(dir, t));
  EXPECT_NE(text.find("**soft**: 75.00% of 16 primitives drawn exactly as the reference "
                      "rasterizer, **1 violating GL's rules** (1 pixels)"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("soft|16|75.00|18.75|1|1|"), std::string::npos) << text;
  EXPECT_NE(text.find("**ref**: no conformance verdict"), std::string::npos) << text;
}

// Why: a refused night's page 1 ran the experiment files' difference into one line ("- seed =
// 2008 + seed = 2009 An experiment changed ..."); a difference reads as a diff, a line each.
TEST(Conclusion, ARefusedNightSetsTheExperimentDifferenceAsABlockOfLines) {
  const an::testing::ScopedTempDir scoped("conclusion_refused");
  const std::string dir = scoped.path.string();
  std::filesystem::create_directories(scoped.path / "audit");
  std::ofstream(scoped.path / "audit" / "refused.txt")
      << "renderaudit: not runs of the same experiment: baseline b has experiment hash 1 (seed "
         "2008), current c has experiment hash 2 (seed 2009); an audit compares the same "
         "primitives, so both runs must come from the same experiment file. Their "
         "experiment.toml files differ in (- baseline, + current):\n"
         "  - seed = 2008\n  + seed = 2009\n"
         "An experiment changed on purpose needs a new baseline: a run of the new experiment "
         "(for the nightly audit: scripts/nightly.sh --promote c)\n";
  const std::vector<Block> blocks = conclusion_blocks(dir, an::RunTally{});
  ASSERT_GE(blocks.size(), 4u);
  EXPECT_EQ(blocks[1].kind, Block::Kind::kParagraph);
  EXPECT_NE(blocks[1].text.find("**Audit: no verdict.**"), std::string::npos) << blocks[1].text;
  EXPECT_NE(blocks[1].text.find("differ in (- baseline, + current):"), std::string::npos);
  EXPECT_EQ(blocks[1].text.find("seed = 2008"), std::string::npos) << blocks[1].text;
  EXPECT_EQ(blocks[2].kind, Block::Kind::kPreformatted);
  EXPECT_EQ(blocks[2].text, "- seed = 2008\n+ seed = 2009");
  EXPECT_EQ(blocks[3].kind, Block::Kind::kParagraph);
  EXPECT_EQ(blocks[3].text.rfind("An experiment changed on purpose", 0), 0u) << blocks[3].text;

  // the HTML sets it as a code block, the PDF a line each
  Document doc;
  doc.title = "night";
  doc.blocks = blocks;
  EXPECT_NE(render_html(doc).find("<pre>- seed = 2008\n+ seed = 2009</pre>"), std::string::npos);
  const std::string pdf = (scoped.path / "night.pdf").string();
  write_text_pdf(doc, pdf, {});
  const std::string text = ra::testing_cli::shell_output("pdftotext '" + pdf + "' -");
  EXPECT_NE(text.find("\n- seed = 2008\n+ seed = 2009\n"), std::string::npos) << text;
}

}  // namespace
}  // namespace ra::report
