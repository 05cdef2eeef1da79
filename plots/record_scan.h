// What the figures and the report need from the records beyond the analysis stage's samples
// (analysis/run_records.h): conformance with the reference rasterizer (`ref_diff`) and the cases
// whose status is not `ok`. One pass over DIR/records/*.csv with metrics/records_reader.h (only the
// cells needed are converted; files on several threads).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace ra::plots {

// Conformance of one platform, kind and view group: records with status `ok` and a reference
// comparison (`ref_diff` not empty).
struct Conformance {
  std::uint64_t compared = 0;   // ok records with a ref_diff
  std::uint64_t identical = 0;  // of them, ref_diff == 0: the pixel set equals the reference's
  std::uint64_t drawn = 0;      // of the compared, those where either rasterizer lit a pixel
                                // (pixels > 0 or ref_diff > 0)
  std::uint64_t drawn_identical = 0;
  // Of the compared, records per conformance verdict (metrics/conformance.h), indexed by
  // ra::Conformance: not compared (schema 2, reference), exact, snapped, within-spec, violation.
  std::uint64_t classes[5] = {};
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
  std::size_t line = 0;     // 1-based line in it
};

struct RecordScan {
  std::uint64_t records = 0;
  std::size_t files = 0;
  // (platform, kind, view_group) -> conformance; view_group 0 = A
  std::map<std::tuple<std::string, std::string, int>, Conformance> conformance;
  // (platform, kind, status) -> number of records with that status (not `ok`)
  std::map<std::tuple<std::string, std::string, std::string>, std::uint64_t> non_ok_counts;
  std::vector<NonOkCase> non_ok_examples;  // the first `max_examples`, by file then line
  // (platform, kind) -> render_us of the `ok` records with a time (microseconds, CPU time of draw +
  // glFinish), all of them and the true-visible ones
  std::map<std::pair<std::string, std::string>, std::vector<double>> render_us, render_us_visible;
  // (platform, kind, view_group) -> the group's views' window and field of view, for labels
  std::map<std::tuple<std::string, std::string, int>, std::string> group_labels;
};

// Scans DIR/records/*.csv (*.csv.tmp ignored). Throws ra::UserError when the directory has no
// records or a file's header is not the records header or a needed cell is malformed
// ("FILE:LINE: what").
RecordScan scan_records(const std::string& run_dir, std::size_t max_examples = 200,
                        unsigned jobs = 0);

}  // namespace ra::plots
