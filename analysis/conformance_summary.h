// Conformance verdicts of a run (records columns conformance, violating_pixels, violated_rules;
// metrics/conformance.h), summarised per platform x kind x view group: the shares of exact,
// snapped, within-spec and violation with Clopper-Pearson 95% intervals, and every violation,
// worst first, with the `renderaudit show` command that draws it. Read from the records files
// directly (only these columns), so analyze pays one pass over them.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <vector>

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

struct ConformanceSummary {
  // (platform, kind, view group) -> counts; kind "point", "line", "triangle".
  std::map<std::tuple<std::string, std::string, int>, ConformanceCounts> groups;
  std::vector<Violation> violations;  // worst first (most pixels), then platform, kind, view, index
  std::uint64_t not_compared = 0;     // ok records without a verdict (reference, schema 2)
};

ConformanceSummary summarize_conformance(const std::vector<std::string>& records_files);

// The table "conformance": one row per platform x kind x view group with a verdict.
stats::Table conformance_table(const ConformanceSummary& s);
// violations.md: the count, then up to `limit` violations worst first, each with its show line.
std::string violations_markdown(const ConformanceSummary& s, const std::string& run_dir,
                                std::size_t limit = 200);

}  // namespace ra::analysis
