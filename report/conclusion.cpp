// The report's conclusion (see the header).
#include "report/conclusion.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "analysis/run_tally.h"
#include "rundir/audit_document.h"
#include "rundir/run_folder.h"
#include "stats/csv_table.h"
#include "util/atomic_file.h"
#include "util/number_text.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace ra::report {
namespace {

Block make_block(Block::Kind kind, const std::string& text = "") {
  Block b;
  b.kind = kind;
  b.text = text;
  return b;
}

std::string percent(std::uint64_t part, std::uint64_t whole) {
  if (whole == 0) return "n/a";
  const double p = 100.0 * double(part) / double(whole);
  // never round a share that is not 100% up to "100.00", nor a non-zero one down to "0.00"
  if (part != whole && p > 99.99) return ">99.99";
  if (part != 0 && p < 0.01) return "<0.01";
  return util::fixed(p, 2);
}

// Per platform: cells of the paper compared, and of those beyond 3 SE (explained or not).
struct PaperAgreement {
  std::size_t compared = 0, differing = 0, unexplained = 0;
};

std::map<std::string, PaperAgreement> paper_agreement(const std::string& analysis_dir) {
  std::map<std::string, PaperAgreement> out;
  const std::string comparison = analysis_dir + "/paper_comparison.csv";
  const std::string differences = analysis_dir + "/paper_differences.csv";
  if (!fs::exists(comparison)) return out;
  const stats::CsvTable c = stats::CsvTable::read_file(comparison);
  const std::size_t cp = c.column("Platform");
  for (std::size_t r = 0; r < c.row_count(); ++r) ++out[c.cell(r, cp)].compared;
  if (fs::exists(differences)) {
    const stats::CsvTable d = stats::CsvTable::read_file(differences);
    const std::size_t dp = d.column("Platform"), why = d.column("Why");
    for (std::size_t r = 0; r < d.row_count(); ++r) {
      PaperAgreement& a = out[d.cell(r, dp)];
      ++a.differing;
      a.unexplained += d.cell(r, why) == "not explained";
    }
  }
  return out;
}

// One sentence per platform: the conclusion in words, before the table that holds its numbers.
std::string finding_sentence(const std::string& platform, const analysis::ConformanceCounts& n,
                             const PaperAgreement& a) {
  std::string s = "**" + platform + "**: ";
  if (n.compared == 0) {
    s += "no conformance verdict (the reference itself, or antialiased)";
  } else {
    s += percent(n.exact, n.compared) + "% of " + std::to_string(n.compared) +
         " primitives drawn exactly as the reference rasterizer, ";
    s += n.violation == 0
             ? "every other one as GL allows: **no violation**"
             : "**" + std::to_string(n.violation) + " violating GL's rules** (" +
                   std::to_string(n.violating_pixels) + " pixels)";
  }
  if (a.compared > 0) {
    s += "; " + std::to_string(a.compared - a.differing) + " of " + std::to_string(a.compared) +
         " cells of the paper's tables agree (within 3 SE of at least one of the paper's "
         "platforms)";
    if (a.differing > 0)
      s += a.unexplained == 0 ? " (the other " + std::to_string(a.differing) + " explained)"
                              : " (" + std::to_string(a.unexplained) + " beyond and not explained)";
  }
  return s + ".";
}

// The findings table: one row per platform with a verdict or a paper comparison; `sentences`
// receives the same per platform in words.
Table findings_table(const std::string& run_dir, const analysis::RunTally& tally,
                     std::vector<std::string>& sentences) {
  std::map<std::string, analysis::ConformanceCounts> per;
  for (const auto& [key, n] : tally.verdicts) {
    analysis::ConformanceCounts& p = per[std::get<0>(key)];
    p.compared += n.compared, p.exact += n.exact, p.snapped += n.snapped;
    p.within_spec += n.within_spec, p.violation += n.violation;
    p.violating_pixels += n.violating_pixels;
  }
  const std::map<std::string, PaperAgreement> paper =
      paper_agreement(rundir::run_folder::analysis(run_dir));
  std::set<std::string> platforms;
  for (const auto& [p, n] : per) platforms.insert(p);
  for (const auto& [p, a] : paper) platforms.insert(p);

  Table t;
  t.title = "What this run found, per platform";
  t.header = {"platform", "primitives judged", "as the reference %", "other, as GL allows %",
              "violations", "violating pixels", "paper cells that agree",
              "differ: explained / not"};
  t.right = {false, true, true, true, true, true, true, false};
  for (const std::string& p : platforms) {
    const auto n = per.count(p) ? per.at(p) : analysis::ConformanceCounts{};
    const auto a = paper.count(p) ? paper.at(p) : PaperAgreement{};
    const bool judged = n.compared > 0;
    sentences.push_back(finding_sentence(p, n, a));
    t.rows.push_back(
        {p, judged ? std::to_string(n.compared) : "not judged",
         judged ? percent(n.exact, n.compared) : "-",
         judged ? percent(n.snapped + n.within_spec, n.compared) : "-",
         judged ? std::to_string(n.violation) : "-",
         judged ? std::to_string(n.violating_pixels) : "-",
         a.compared ? std::to_string(a.compared - a.differing) + " of " + std::to_string(a.compared)
                    : "not compared",
         a.compared ? std::to_string(a.differing - a.unexplained) + " / " +
                          std::to_string(a.unexplained)
                    : "-"});
  }
  t.notes.push_back(
      "As the reference: the same pixels as the exact reference rasterizer; other, as GL allows: "
      "other pixels, each one GL permits (the driver's subpixel snapping, ties, line ends); a "
      "violation lights or leaves dark a pixel no conforming implementation could (section 4 lists them, with the command that "
      "draws each). The reference platform is exact by definition; antialiased platforms are not "
      "judged.");
  if (!paper.empty())
    t.notes.push_back(
        "Paper cells: the medians and IQRs of the paper's Tables 3-10 that this run's views "
        "reproduce. A cell agrees within 3 standard errors of at least one of the paper's "
        "platforms; it differs beyond 3 SE of every one, with the reason established for it "
        "(section 'Beside the paper': paper_differences). Every page counts cells this way.");
  return t;
}

// The audit's refusal (the text of audit/refused.txt): its sentences as paragraphs, its indented
// lines (the experiment files' difference, "- seed = 2008", "+ seed = 2009") as a block of their
// own, one line each, as a diff reads.
std::vector<Block> refusal_blocks(const std::string& text) {
  std::vector<Block> out;
  std::string paragraph = "**Audit: no verdict.** The audit refused to compare this run with its "
                          "baseline: ", diff;
  const auto flush_paragraph = [&] {
    while (!paragraph.empty() && paragraph.back() == ' ') paragraph.pop_back();
    if (!paragraph.empty()) out.push_back(make_block(Block::Kind::kParagraph, paragraph));
    paragraph.clear();
  };
  const auto flush_diff = [&] {
    if (!diff.empty()) out.push_back(make_block(Block::Kind::kPreformatted, diff));
    diff.clear();
  };
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("renderaudit: ", 0) == 0) line.erase(0, 13);
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    if (line[0] == ' ' || line[0] == '\t') {  // a line of the difference
      flush_paragraph();
      const std::size_t b = line.find_first_not_of(" \t");
      diff += (diff.empty() ? "" : "\n") + line.substr(b);
      continue;
    }
    flush_diff();
    paragraph += line + " ";
  }
  flush_paragraph();
  flush_diff();
  return out;
}

// The audit's verdict per driver, against the baseline it names.
std::vector<Block> audit_blocks(const std::string& run_dir) {
  std::vector<Block> out;
  const std::string path = rundir::run_folder::audit_json(rundir::run_folder::audit(run_dir));
  // the nightly audit's refusal
  const std::string refused = rundir::run_folder::audit(run_dir) + "/refused.txt";
  if (!fs::exists(path) && fs::exists(refused)) {
    return refusal_blocks(util::read_file(refused));
  }
  if (!fs::exists(path)) return out;
  const rundir::AuditDocument a = rundir::read_audit_document(rundir::run_folder::audit(run_dir));
  const std::string& verdict = a.verdict;
  const std::string& baseline_dir = a.baseline_dir;
  if (verdict == "baseline") {  // the run audited against itself: no verdict about any driver
    out.push_back(make_block(
        Block::Kind::kParagraph,
        "**Audit: baseline established: nothing compared.** This run is the baseline of its "
        "series (the first run of a nightly audit): later runs are audited against it, and their "
        "reports give a verdict per driver. Its own crash and timeout records, if any, are in "
        "audit/audit.md."));
    return out;
  }
  out.push_back(make_block(
      Block::Kind::kParagraph,
      "**Audit: " + verdict + "** against the baseline run " + baseline_dir +
          ". Per driver, PASS when no primitive changed, no primitive or shard failed and no shard "
          "is missing; the details are in audit/audit.md."));
  struct Driver {
    std::string baseline;
    std::int64_t compared = 0, changed = 0, flakes = 0, failed = 0;
  };
  std::map<std::string, Driver> drivers;
  for (const rundir::AuditDocument::ViewRow& v : a.views) {
    Driver& d = drivers[v.platform];
    d.baseline = v.baseline_platform;
    d.compared += v.compared;
    d.changed += v.changed;
    d.flakes += v.flakes;
    d.failed += v.failed;
  }
  std::map<std::string, std::int64_t> missing;
  for (const std::string& p : a.missing_shard_platforms) ++missing[p];
  // shard failures the manifest lists that did not recover on re-run count against their driver
  for (const rundir::AuditDocument::ShardFailure& m : a.manifest_failures)
    if (m.outcome != "recovered") ++drivers[m.platform].failed;
  std::set<std::string> mismatched;
  for (const std::string& m : a.renderer_mismatches)  // "PLATFORM: ..."
    mismatched.insert(m.substr(0, m.find(':')));
  Table t;
  t.title = "Audit verdict per driver";
  t.header = {"platform", "baseline platform", "verdict", "compared", "changed", "flaky",
              "failed (primitives, shards)", "missing shards"};
  t.right = {false, false, false, true, true, true, true, true};
  // Drawing time (audit --speed): a group that draws slower fails its driver unless the audit
  // made that a warning.
  std::set<std::string> slower;
  for (const rundir::AuditedTime& row : a.speed)
    if (row.verdict == "slower" && !a.speed_warn_only) slower.insert(row.platform);
  for (const auto& [p, d] : drivers) {
    const std::int64_t miss = missing.count(p) ? missing.at(p) : 0;
    const bool pass = d.changed == 0 && d.failed == 0 && miss == 0 && !mismatched.count(p) &&
                      !slower.count(p);
    t.rows.push_back({p, d.baseline, pass ? "PASS" : "FAIL", std::to_string(d.compared),
                      std::to_string(d.changed), std::to_string(d.flakes),
                      std::to_string(d.failed), std::to_string(miss)});
  }
  if (!mismatched.empty())
    t.notes.push_back("A driver whose GL_RENDERER does not match --expect-renderer fails.");
  for (const std::string& r : a.reasons) t.notes.push_back(r);
  if (!slower.empty()) t.notes.push_back("A driver that draws a kind and view group slower fails.");
  Block b = make_block(Block::Kind::kTable);
  b.table = std::move(t);
  out.push_back(std::move(b));
  if (a.speed.empty()) return out;
  Table time;
  time.title = "Drawing time against the baseline";
  time.header = {"platform", "kind", "group", "current / baseline [95%]", "verdict"};
  time.right = {false, false, false, true, false};
  auto fixed3 = [](double v) {
    if (!std::isfinite(v)) return std::string("-");
    char text[32];
    std::snprintf(text, sizeof text, "%.3f", v);
    return std::string(text);
  };
  for (const rundir::AuditedTime& row : a.speed)
    time.rows.push_back({row.platform, row.kind, row.group,
                         fixed3(row.ratio) + " [" + fixed3(row.low) + ", " + fixed3(row.high) + "]",
                         row.verdict});
  time.notes.push_back(
      "Each primitive drawn alone by both sides and a control (the baseline again), in rounds "
      "of fresh processes taking turns; the ratio and its 95% interval come from the rounds' "
      "paired estimates. Slower or faster only when the whole interval lies beyond the "
      "threshold and the control's own ratio; audit/audit.md has the control, the tests and the "
      "method.");
  Block tb = make_block(Block::Kind::kTable);
  tb.table = std::move(time);
  out.push_back(std::move(tb));
  return out;
}

}  // namespace

std::vector<Block> conclusion_blocks(const std::string& run_dir, const analysis::RunTally& tally) {
  std::vector<Block> out;
  Block h = make_block(Block::Kind::kHeading, "Conclusion");
  h.level = 2;  // on the title page (a level-1 heading would start a page)
  h.anchor = "conclusion";
  out.push_back(std::move(h));
  for (Block& b : audit_blocks(run_dir)) out.push_back(std::move(b));
  std::vector<std::string> sentences;
  Block t = make_block(Block::Kind::kTable);
  t.table = findings_table(run_dir, tally, sentences);
  Block list = make_block(Block::Kind::kBullets);
  list.items = std::move(sentences);
  out.push_back(std::move(list));
  // the table's notes after the picture, so that the picture fits on the first page
  Block notes = make_block(Block::Kind::kNotes);
  notes.items = std::move(t.table.notes);
  t.table.notes.clear();
  out.push_back(std::move(t));
  // The finding as a picture: where each driver's pixels differ from the reference's.
  const std::string overview = rundir::run_folder::figures(run_dir) + "/conformance.overview.png";
  if (fs::exists(overview)) {
    Block image = make_block(Block::Kind::kImage,
                             "Where each driver lights other pixels than the exact reference "
                             "rasterizer, per kind and view group (percent of the records; the "
                             "rest are identical). Section 4 says which of them GL allows.");
    image.image_path = fs::absolute(overview).string();
    image.image_href = "../figures/conformance.overview.png";
    image.image_height_fraction = 0.45;
    out.push_back(std::move(image));
  }
  out.push_back(std::move(notes));
  return out;
}

}  // namespace ra::report
