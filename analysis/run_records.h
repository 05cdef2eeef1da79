// The records of a run directory (DIR/records/*.csv.zst or *.csv, schema in docs/records.md and
// metrics/records.h), loaded as the samples the analysis stage needs and nothing more: per platform, kind and view the
// visibility-class counts, the values of each error metric over the true-visible cases with status
// `ok` (float64, in record units), and the render times. Views that differ only by camera
// orientation (the same `view_group`) are gathered into view groups A, B, C, ... (paper, section 4:
// "View A is the aggregate of views 1 and 2").
//
// Reading: the columns are located by name in records_header() (metrics/records.h stays the single
// definition of the schema) and every file's header must equal it. The files are parsed in parallel
// with std::from_chars (locale-independent, exact); only the columns used here are converted, and
// each of those is validated: a malformed record is a ra::util::UserError "FILE:LINE: what is wrong".
// Records are checked for consistency: a view has the same parameters in every record of every
// file, the views of a group share field of view, window and clip planes, and no (platform, kind,
// view, index) appears twice (a copied shard would be counted twice otherwise).
//
// Units: PE, LSEs, LSEu and TEu-edge-norm in pixels; TEs, TEu in pixels^2; *_norm divide lengths by
// sqrt(W*H) and areas by W*H (normalised window coordinates, paper section 3.2); render_us in
// microseconds of CPU time (GL: draw + glFinish; Vulkan: record + submit + fence wait).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "analysis/conformance_summary.h"
#include "geometry/primitive.h"
#include "rundir/experiment.h"
#include "rundir/shard_file.h"
#include "stats/descriptive.h"
#include "util/parallel.h"

namespace ra::analysis {

// The kind of a record is the project's one primitive kind, geometry::Kind (geometry/primitive.h);
// records spell it with kind_name: "point", "line", "triangle".
constexpr std::size_t kKindCount = 3;
constexpr std::array<geometry::Kind, kKindCount> kAllKinds = {
    geometry::Kind::kPoint, geometry::Kind::kLine, geometry::Kind::kTriangle};
using ra::geometry::kind_name;

// "points", "line segments", "triangles": the words of the paper's captions, for table titles.
const char* kind_label_plural(geometry::Kind kind);

// What a metric's values measure, for unit labels and conversions to physical units.
enum class MetricUnit {
  kPixels,            // a length in pixels
  kSquarePixels,      // an area in pixels^2
  kNormalizedLength,  // a length / sqrt(W*H)
  kNormalizedArea,    // an area / (W*H)
};
const char* unit_name(MetricUnit unit);  // "px", "px^2", "sqrt(W*H) units", "W*H units"

// One error-metric column of the records.
struct MetricSpec {
  const char* column;       // records column, e.g. "pe_norm"
  geometry::Kind kind;      // the kind whose records carry it
  const char* symbol;       // the paper's symbol, e.g. "PEnorm"
  const char* description;  // e.g. "normalized point rendering error"
  MetricUnit unit;
};

// The metrics analysed for a kind, the paper's headline ones first: points PE, PEnorm; lines
// LSEs-norm, LSEu-norm, LSEs, LSEu; triangles TEs-norm, TEu-norm, TEs, TEu, TEu-edge-norm (TEu per
// pixel of visible edge, pixels).
const std::vector<MetricSpec>& kind_metrics(geometry::Kind kind);

// The index of `column` in kind_metrics(kind); std::logic_error when it is not one of them.
std::size_t metric_index(geometry::Kind kind, std::string_view column);

// The parameters of one view (docs/records.md).
struct ViewMeta {
  int view = 0;         // 1-based, Table 1 order
  int view_group = 0;   // 0 = A
  int orientation = 0;  // 1-based camera orientation
  double fov_deg = 0;
  int width = 0, height = 0;  // pixels
  double near = 0, far = 0;   // world units
};

// Counts of one platform, kind and view. The five classes count records with status `ok` only; the
// other statuses are counted apart (their visibility means nothing).
struct VisibilityCounts {
  std::array<std::uint64_t, 5> by_class{};  // indexed by int(ra::Visibility)
  std::uint64_t invalid = 0, crash = 0, timeout = 0;
  std::uint64_t total() const;
};

// The samples of one platform, kind and view.
struct ViewData {
  ViewMeta meta;
  VisibilityCounts counts;
  // values[m]: metric kind_metrics(kind)[m] over true-visible `ok` records whose cell is not empty,
  // ascending (no statistic here depends on the record order; sorted once at loading, every later
  // quantile is cheap, and results do not depend on the order in which files were read)
  std::vector<std::vector<double>> values;
  // missing[m]: true-visible `ok` records whose cell of metric m is empty (metric not yet measured)
  std::vector<std::uint64_t> missing;
  std::vector<double> render_us_visible;  // true-visible `ok` records with a time, us, ascending
  std::vector<double> render_us_other;    // the other `ok` records with a time, ascending
};

struct ViewKey {
  std::size_t platform = 0;  // index into RunRecords::platforms
  geometry::Kind kind = geometry::Kind::kPoint;
  int view = 0;
  bool operator<(const ViewKey& o) const;
};

// The views of one platform and kind that differ only by camera orientation.
struct ViewGroup {
  std::size_t platform = 0;
  geometry::Kind kind = geometry::Kind::kPoint;
  int view_group = 0;
  std::string label;                   // "A", "B", ... (ra::View::group_name)
  std::vector<const ViewData*> views;  // ascending by orientation, then view number
  const ViewMeta& meta() const { return views.front()->meta; }  // fov, window, planes of all
  std::size_t count(std::size_t metric) const;  // values of a metric over the group's views
  std::vector<double> pooled(std::size_t metric) const;  // the views' values merged, ascending
  VisibilityCounts counts() const;                       // summed over the views
  std::vector<int> view_numbers() const;
};

struct RunRecords {
  RunRecords() = default;
  RunRecords(const RunRecords&) = delete;  // groups point into views
  RunRecords& operator=(const RunRecords&) = delete;
  RunRecords(RunRecords&&) = default;
  RunRecords& operator=(RunRecords&&) = default;

  std::string run_dir;
  std::vector<std::string> files;      // the records files read, sorted
  std::uint64_t record_count = 0;      // rows read
  std::vector<std::string> platforms;  // sorted by name: Platform I, II, ... in the tables
  std::map<ViewKey, ViewData> views;
  std::vector<ViewGroup> groups;  // by platform, kind, view_group
  double point_margin_px = 0;             // LoadOptions::point_margin_px applied
  std::uint64_t points_within_margin = 0;  // true-invisible points counted false-invisible by it
  // The conformance verdicts and what is tallied beside them (every record, any status), from the
  // same pass over the files; NonOkCase::file relative to run_dir.
  ConformanceSummary conformance;
  // Each file's seal by file name, when LoadOptions::read_seals (check_run_completeness takes it).
  std::map<std::string, rundir::ShardSeal> seals;

  // The kinds that have at least one record, in kAllKinds order.
  std::vector<geometry::Kind> kinds() const;
  // The groups of one platform and kind, ascending by view_group.
  std::vector<const ViewGroup*> groups_of(std::size_t platform, geometry::Kind kind) const;
  // The group, or nullptr.
  const ViewGroup* find_group(std::size_t platform, geometry::Kind kind, int view_group) const;
  // The view groups numbers present for a kind on any platform, ascending.
  std::vector<int> view_groups(geometry::Kind kind) const;
};

struct LoadOptions {
  unsigned jobs = 0;  // threads parsing files; 0: the number of cores
  // The paper's point convention (metrics/point_metrics.h, inside_window_margin): an `ok`
  // true-invisible point whose projection lies within this many pixels outside the window is
  // counted false-invisible instead. 0: the records' own classes. Needs `experiment` (the run's
  // views and seed, from which each point is generated again by its index).
  double point_margin_px = 0;
  const rundir::Experiment* experiment = nullptr;
  // Also read each file's seal (rundir/shard_file.h) in the same pass, into RunRecords::seals, so
  // that the completeness check need not read the files again.
  bool read_seals = false;
};

// Loads DIR/records/*.csv (*.csv.tmp, unfinished shards, are ignored). Throws ra::util::UserError when
// DIR or DIR/records does not exist, holds no records file, or a file is malformed or inconsistent
// (message "FILE:LINE: what", or naming both files of an inconsistency).
RunRecords load_run_records(const std::string& run_dir, const LoadOptions& options = {});

// "A", "B", ..., "Z", "AA", ... for view_group 0, 1, ...
std::string view_group_label(int view_group);

// stats::describe() of an ascending, non-empty vector without sorting it again (the samples here
// are kept sorted). std::logic_error when `ascending` is empty or not ascending.
stats::Description describe_sorted(const std::vector<double>& ascending,
                                   stats::QuantileDefinition definition);

// The ascending vectors `parts` merged into one ascending vector.
std::vector<double> merge_sorted(const std::vector<const std::vector<double>*>& parts);

// What render_us means on a Vulkan platform (vk-*), for the notes of the tables and report
// sections that show it when a run has one.
extern const char* const kVulkanRenderTimeNote;
// What render_us is on the device's clock (records column clock).
extern const char* const kDeviceClockNote;
bool is_vulkan_platform(const std::string& platform);

}  // namespace ra::analysis
