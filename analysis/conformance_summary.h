// Conformance verdicts of a run (records columns conformance, violating_pixels, violated_rules;
// metrics/conformance.h), summarised per platform x kind x view group: the shares of exact,
// snapped, within-spec and violation with Clopper-Pearson 95% intervals, and every violation,
// worst first, with the `renderaudit show` command that draws it. The same pass also tallies what
// plot and report show beside the verdicts: agreement with the reference rasterizer (ref_diff),
// each view group's camera label and the records whose status is not `ok`. Tallied row by row
// (ConformanceTally) in the pass that loads the records for the statistics (run_records.h), so
// analyze reads every file once.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "rundir/records_reader.h"
#include "stats/table_writer.h"

namespace ra::analysis {

struct ConformanceCounts {
  std::uint64_t compared = 0;  // records with a verdict (status ok, platform not the reference)
  std::uint64_t exact = 0, snapped = 0, within_spec = 0, violation = 0;
  std::uint64_t violating_pixels = 0;
  std::map<std::string, std::uint64_t> rules;  // records breaking each rule
};

struct Violation {
  std::string platform, kind;
  int view = 0, view_group = 0;
  std::uint64_t index = 0;
  std::int64_t violating_pixels = 0;
  std::string rules;
};

// Agreement with the reference rasterizer of one platform, kind and view group: records with status
// `ok` and a reference comparison (`ref_diff` not empty).
struct ReferenceAgreement {
  std::uint64_t compared = 0;   // ok records with a ref_diff
  std::uint64_t identical = 0;  // of them, ref_diff == 0: the pixel set equals the reference's
  std::uint64_t drawn = 0;      // of the compared, those where either rasterizer lit a pixel
                                // (pixels > 0 or ref_diff > 0)
  std::uint64_t drawn_identical = 0;
  // Share identical, in [0, 1]; 0 when nothing was compared.
  double rate() const { return compared ? double(identical) / double(compared) : 0; }
  double drawn_rate() const { return drawn ? double(drawn_identical) / double(drawn) : 0; }
};

// A record whose status is not `ok` (invalid, crash, timeout).
struct NonOkCase {
  std::string platform, kind, status;
  int view = 0;
  std::uint64_t index = 0;  // primitive index under the seed
  std::string file;         // records file, relative to the run directory
  std::uint64_t line = 0;   // 1-based line in it
};

using GroupKey = std::tuple<std::string, std::string, int>;  // platform, kind, view group (0 = A)

struct ConformanceSummary {
  // (platform, kind, view group) -> counts; kind "point", "line", "triangle".
  std::map<std::tuple<std::string, std::string, int>, ConformanceCounts> groups;
  std::vector<Violation> violations;  // worst first (most pixels), then platform, kind, view, index
  std::uint64_t not_compared = 0;     // ok records without a verdict (reference, schema 2)
  std::map<GroupKey, ReferenceAgreement> reference;
  // Every group's views' field of view and window as the records spell them, "60 deg, 128x128",
  // from the group's first record (files in the given order).
  std::map<GroupKey, std::string> group_labels;
  // (platform, kind, status) -> number of records with that status (not `ok`)
  std::map<std::tuple<std::string, std::string, std::string>, std::uint64_t> non_ok_counts;
  std::vector<NonOkCase> non_ok_examples;  // the first kNonOkExamples, by file then line
};

constexpr std::size_t kNonOkExamples = 30;

// `records_files` in the order their records count (sorted, as load_run_records lists them);
// NonOkCase::file is relative to `run_dir` when that is given.
// Used by tests as an independent check of ConformanceTally (a pass of its own over the files).
ConformanceSummary summarize_conformance(const std::vector<std::string>& records_files,
                                         const std::string& run_dir = "");

// The summary of one records file, row by row, so that the pass that loads the records for the
// statistics (load_run_records) tallies the verdicts too; the files' tallies are then joined in
// file order with append_conformance. `file` is NonOkCase::file for this file's rows.
class ConformanceTally {
 public:
  explicit ConformanceTally(std::string file) : file_(std::move(file)) {}
  void add(const rundir::RecordRow& row);
  ConformanceSummary take() { return std::move(summary_); }

 private:
  void select_group(std::string_view platform, std::string_view kind, int group);

  std::string file_;
  ConformanceSummary summary_;
  // the group of the previous row (rows come in runs of one platform, kind and view) and its
  // entries, made when first needed so that a group without verdicts gets no row
  GroupKey key_{"", "", -1};
  ConformanceCounts* counts_ = nullptr;
  ReferenceAgreement* reference_ = nullptr;
};

// Appends a later file's summary: counts added, the first label of each group kept, examples of
// records that are not `ok` up to kNonOkExamples, violations appended (then ordered by
// finish_conformance).
void append_conformance(ConformanceSummary& into, ConformanceSummary&& later);
// Orders the violations worst first (ConformanceSummary::violations).
void finish_conformance(ConformanceSummary& s);

// The table "conformance": one row per platform x kind x view group with a verdict.
stats::Table conformance_table(const ConformanceSummary& s);
// violations.md: the count, then up to `limit` violations worst first, each with its show line.
std::string violations_markdown(const ConformanceSummary& s, const std::string& run_dir,
                                std::size_t limit = 200);

}  // namespace ra::analysis
