// What plot and report show of a run beside the figure data: the number of records and files, per
// platform, kind and view group the GL verdicts, the agreement with the reference rasterizer and
// the camera label, the records whose status is not `ok`, and per platform and kind the render time
// (microseconds of CPU time, draw + glFinish). `analyze` computes it (from load_run_records and the
// conformance pass, so no later stage reads the records again) and writes it into figures.json as
// "tally" (analysis/figure_data.h documents the keys); plot and report read it back.
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "analysis/conformance_summary.h"
#include "analysis/run_records.h"

namespace ra::analysis {

// Render time of one platform and kind over the `ok` records with a time.
struct RenderTime {
  std::uint64_t cases = 0;         // records with a time
  double median_us = 0, iqr_us = 0;  // Hyndman-Fan 6 quartiles
  std::uint64_t true_visible = 0;  // of them, true-visible
  std::optional<double> median_us_true_visible;  // none when no true-visible record has a time
};

struct RunTally {
  std::uint64_t records = 0, files = 0;
  std::map<GroupKey, ConformanceCounts> verdicts;  // ConformanceCounts::rules left empty
  std::map<GroupKey, ReferenceAgreement> reference;
  std::map<GroupKey, std::string> group_labels;  // "60 deg, 128x128"
  std::map<std::tuple<std::string, std::string, std::string>, std::uint64_t> non_ok_counts;
  std::vector<NonOkCase> non_ok_examples;  // the first ones, by file then line
  std::map<std::pair<std::string, std::string>, RenderTime> render_time;  // (platform, kind)
};

RunTally tally_run(const RunRecords& run, const ConformanceSummary& conformance);

nlohmann::json tally_json(const RunTally& tally);
// The "tally" of a figures.json document read from `path`; ra::UserError naming the file and the key
// when it is missing or of the wrong type.
RunTally read_tally(const nlohmann::json& figures, const std::string& path);

// DIR/analysis/figures.json, parsed and checked for its schema and version. ra::UserError saying to
// run `renderaudit analyze DIR` (first, or again) when it is missing, not JSON or of another version.
nlohmann::json read_figures_json(const std::string& run_dir);

}  // namespace ra::analysis
