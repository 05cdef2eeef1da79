// What plot and report show of a run beside the figure data: the number of records and files, per
// platform, kind and view group the GL verdicts, the agreement with the reference rasterizer and
// the camera label, the records whose status is not `ok`, and per platform and kind the render time
// (render_us, microseconds on the clock the records' `clock` names: the host's draw + wait, or the
// device's timer). `analyze` computes it (from load_run_records and the
// conformance pass, so no later stage tallies the records again) and writes
// DIR/analysis/tally.json; plot and report read it back.
//
// tally.json, schema "renderaudit-tally", schema_version 1 (rundir/manifest.h document_header):
// {
//   "schema": "renderaudit-tally", "schema_version": 1,
//   "records": 64000, "files": 32,
//   "groups": [                       // every platform, kind and view group with a record
//     {"platform": "...", "kind": "line", "view_group": "A", "view_group_index": 0,
//      "label": "30 deg, 128x128",    // fov_deg, width, height as the records spell them
//      "reference": {"compared": .., "identical": .., "drawn": .., "drawn_identical": ..},
//                                     // ok records with a ref_diff (ReferenceAgreement); absent
//                                     // when none
//      "verdicts": {"judged": .., "exact": .., "snapped": .., "within_spec": .., "violation": ..,
//                   "violating_pixels": ..}}],  // ok records with a verdict; absent when none
//   "non_ok": [{"platform": "...", "kind": "...", "status": "crash", "records": 3}],
//   "non_ok_examples": [              // the first 30, by file then line
//     {"platform": "...", "kind": "...", "status": "...", "view": 1, "index": 17,
//      "file": "records/NAME.csv", "line": 18}],
//   "render_time": [                  // ok records with a time, per platform and kind
//     {"platform": "...", "kind": "...", "cases": .., "median_us": .., "iqr_us": ..,  // HF6
//      "true_visible": .., "median_us_true_visible": ..}]   // null when none
// }
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
  std::uint64_t cases = 0;                       // records with a time
  double median_us = 0, iqr_us = 0;              // Hyndman-Fan 6 quartiles
  std::uint64_t true_visible = 0;                // of them, true-visible
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

constexpr int kTallySchemaVersion = 1;

// The document tally.json holds.
nlohmann::json tally_json(const RunTally& tally);
// DIR/analysis/tally.json. ra::util::UserError saying to run `renderaudit analyze DIR` (first, or again)
// when it is missing, not JSON, of another schema version, or lacks a key.
RunTally read_tally(const std::string& run_dir);

}  // namespace ra::analysis
