// Loading a run directory's records into samples (load_run_records, run_records.h).
//
// Speed: the analysis needs 14 of the 39 columns, so each row is read with rundir/records_reader.h
// (split in place, only those cells converted) and files are parsed on several threads.
#include "analysis/run_records.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <tuple>

#include "rundir/records_format.h"
#include "rundir/run_folder.h"
#include "util/errors.h"
#include "metrics/records.h"
#include "rundir/records_reader.h"
#include "geometry/view.h"
#include "metrics/point_metrics.h"
#include "util/cell_text.h"

namespace fs = std::filesystem;

namespace ra::analysis {

namespace {

// The records column of each metric of each kind (kind_metrics names them).
using MetricColumns = std::array<std::vector<metrics::RecordColumn>, kKindCount>;

MetricColumns make_metric_columns() {
  MetricColumns columns;
  for (geometry::Kind k : kAllKinds) {
    for (const MetricSpec& m : kind_metrics(k)) {
      const std::optional<metrics::RecordColumn> c = metrics::find_record_column(m.column);
      if (!c) {
        throw std::logic_error("metrics/records.h has no column '" + std::string(m.column) +
                               "': the analysis stage must follow the schema change");
      }
      columns[static_cast<std::size_t>(k)].push_back(*c);
    }
  }
  return columns;
}

const MetricColumns& metric_columns() {
  static const MetricColumns columns = make_metric_columns();
  return columns;
}

// One view's data as read from one file (or merged from several).
struct PartialView {
  ViewData data;
  std::vector<std::uint64_t> indices;  // primitive indices, to find records counted twice
  std::uint64_t min_index = UINT64_MAX, max_index = 0;
  std::int64_t meta_line = 0;  // line of the file where the view's parameters were first read
  std::vector<std::string> meta_text;  // those parameter cells as written, for a fast comparison
};

using PartialKey = std::tuple<std::string, int, int>;  // platform, kind, view

struct FileChunk {
  std::map<PartialKey, PartialView> views;
  std::uint64_t records = 0;
  std::uint64_t points_within_margin = 0;  // LoadOptions::point_margin_px reclassifications
  ConformanceSummary conformance;
  std::optional<rundir::ShardSeal> seal;  // LoadOptions::read_seals
};

// Difference between two views' parameters, "" when equal.
std::string meta_difference(const ViewMeta& here, const ViewMeta& there) {
  const auto num = [](double v) { return util::full_precision(v); };
  if (here.view_group != there.view_group)
    return "view_group " + std::to_string(here.view_group) + " here but " +
           std::to_string(there.view_group);
  if (here.orientation != there.orientation)
    return "orientation " + std::to_string(here.orientation) + " here but " +
           std::to_string(there.orientation);
  if (here.fov_deg != there.fov_deg)
    return "fov_deg " + num(here.fov_deg) + " here but " + num(there.fov_deg);
  if (here.width != there.width || here.height != there.height)
    return "window " + std::to_string(here.width) + "x" + std::to_string(here.height) +
           " here but " + std::to_string(there.width) + "x" + std::to_string(there.height);
  if (here.near != there.near) return "near " + num(here.near) + " here but " + num(there.near);
  if (here.far != there.far) return "far " + num(here.far) + " here but " + num(there.far);
  return "";
}

// A view's parameters: the cells compared between its records.
constexpr std::array<metrics::RecordColumn, 7> kMetaColumns = {
    metrics::RecordColumn::kViewGroup, metrics::RecordColumn::kOrientation,
    metrics::RecordColumn::kFovDeg,    metrics::RecordColumn::kWidth,
    metrics::RecordColumn::kHeight,    metrics::RecordColumn::kNear,
    metrics::RecordColumn::kFar};

class FileParser {
 public:
  // `name`: the file as the conformance summary names it (relative to the run directory).
  FileParser(const std::string& path, const std::string& name, const MetricColumns& metrics,
             const LoadOptions& options)
      : path_(path), metrics_(metrics), options_(options), conformance_(name) {}

  FileChunk parse() {
    const auto row = [this](const rundir::RecordRow& r) { record(r); };
    if (options_.read_seals) {
      rundir::ShardSealReader seal;
      rundir::for_each_record_row(path_, row,
                                   [&seal](std::string_view text) { seal.add(text); });
      chunk_.seal = seal.finish();
    } else {
      rundir::for_each_record_row(path_, row);
    }
    chunk_.conformance = conformance_.take();
    return std::move(chunk_);
  }

 private:
  void record(const rundir::RecordRow& row) {
    ++chunk_.records;
    conformance_.add(row);
    const std::string_view platform = row.cell(metrics::RecordColumn::kPlatform);
    if (platform.empty()) row.fail("column 'platform' is empty");
    const std::optional<geometry::Kind> kind =
        geometry::parse_kind(row.cell(metrics::RecordColumn::kKind), geometry::KindSpelling::kName);
    if (!kind) {
      row.fail("unknown kind '" + std::string(row.cell(metrics::RecordColumn::kKind)) +
               "' (allowed: point, line, triangle)");
    }
    const int view = row.integer<int>(metrics::RecordColumn::kView);
    if (view < 1) {
      row.fail("column 'view': " + std::to_string(view) + " is not a view number (>= 1)");
    }

    if (current_ == nullptr || platform != current_platform_ || *kind != current_kind_ ||
        view != current_view_) {
      current_platform_.assign(platform);
      current_kind_ = *kind;
      current_view_ = view;
      auto [it, inserted] =
          chunk_.views.try_emplace(PartialKey{current_platform_, static_cast<int>(*kind), view});
      current_ = &it->second;
      if (inserted) {
        const std::size_t metrics = kind_metrics(*kind).size();
        current_->data.values.resize(metrics);
        current_->data.missing.assign(metrics, 0);
        current_->data.meta = read_meta(row, view);
        current_->meta_line = row.line();
        for (metrics::RecordColumn c : kMetaColumns) current_->meta_text.emplace_back(row.cell(c));
      } else {
        check_meta(row, view);
      }
    } else {
      check_meta(row, view);
    }
    PartialView& pv = *current_;

    const std::uint64_t index = row.integer<std::uint64_t>(metrics::RecordColumn::kIndex);
    pv.indices.push_back(index);
    pv.min_index = std::min(pv.min_index, index);
    pv.max_index = std::max(pv.max_index, index);

    const metrics::CaseStatus status = row.status();
    const metrics::Visibility visibility = row.visibility();
    VisibilityCounts& counts = pv.data.counts;
    switch (status) {
      case metrics::CaseStatus::kOk:
        break;
      case metrics::CaseStatus::kInvalid:
        ++counts.invalid;
        return;
      case metrics::CaseStatus::kCrash:
        ++counts.crash;
        return;
      case metrics::CaseStatus::kTimeout:
        ++counts.timeout;
        return;
    }
    const metrics::Visibility counted = paper_point_class(*kind, view, index, visibility);
    ++counts.by_class[static_cast<std::size_t>(counted)];
    const bool visible = visibility == metrics::Visibility::kTrueVisible;
    if (const std::optional<double> t = row.number(metrics::RecordColumn::kRenderUs)) {
      (visible ? pv.data.render_us_visible : pv.data.render_us_other).push_back(*t);
    }
    if (!visible) return;
    const std::vector<metrics::RecordColumn>& columns = metrics_[static_cast<std::size_t>(*kind)];
    for (std::size_t m = 0; m < columns.size(); ++m) {
      if (const std::optional<double> x = row.number(columns[m])) {
        pv.data.values[m].push_back(*x);
      } else {
        ++pv.data.missing[m];
      }
    }
  }

  // The class under LoadOptions::point_margin_px: a true-invisible point within the margin outside
  // the window is false-invisible (nothing is drawn outside a window, so it is never lit).
  metrics::Visibility paper_point_class(geometry::Kind kind, int view, std::uint64_t index,
                                        metrics::Visibility visibility) {
    if (options_.point_margin_px <= 0 || kind != geometry::Kind::kPoint ||
        visibility != metrics::Visibility::kTrueInvisible)
      return visibility;
    const rundir::Experiment& e = *options_.experiment;
    if (view > int(e.views.size()))
      throw util::UserError(path_ + ": view " + std::to_string(view) +
                            " is not in the run's experiment (" + std::to_string(e.views.size()) +
                            " views)");
    const geometry::Primitive point = make_primitive(e.seed, geometry::Kind::kPoint, index);
    if (!metrics::inside_window_margin(e.views[std::size_t(view - 1)], point.v[0],
                                       options_.point_margin_px))
      return visibility;
    ++chunk_.points_within_margin;
    return metrics::Visibility::kFalseInvisible;
  }

  static ViewMeta read_meta(const rundir::RecordRow& row, int view) {
    ViewMeta m;
    m.view = view;
    m.view_group = row.integer<int>(metrics::RecordColumn::kViewGroup);
    m.orientation = row.integer<int>(metrics::RecordColumn::kOrientation);
    m.fov_deg = row.required_number(metrics::RecordColumn::kFovDeg);
    m.width = row.integer<int>(metrics::RecordColumn::kWidth);
    m.height = row.integer<int>(metrics::RecordColumn::kHeight);
    m.near = row.required_number(metrics::RecordColumn::kNear);
    m.far = row.required_number(metrics::RecordColumn::kFar);
    if (m.view_group < 0) {
      row.fail("column 'view_group': " + std::to_string(m.view_group) + " < 0");
    }
    if (m.width < 1 || m.height < 1) row.fail("the window must be at least 1x1 pixels");
    return m;
  }

  void check_meta(const rundir::RecordRow& row, int view) const {
    // the same text as the first record of the view: the same parameters (the usual case, and
    // cheaper than converting 7 numbers per record); otherwise compare the numbers
    bool same_text = true;
    for (std::size_t i = 0; i < kMetaColumns.size() && same_text; ++i) {
      same_text = row.cell(kMetaColumns[i]) == current_->meta_text[i];
    }
    if (same_text) return;
    const std::string diff = meta_difference(read_meta(row, view), current_->data.meta);
    if (!diff.empty()) {
      row.fail("view " + std::to_string(view) + " (" + current_platform_ + ", " +
               kind_name(current_kind_) + ") has " + diff + " on line " +
               std::to_string(current_->meta_line));
    }
  }

  const std::string& path_;
  const MetricColumns& metrics_;
  const LoadOptions& options_;
  FileChunk chunk_;
  ConformanceTally conformance_;
  PartialView* current_ = nullptr;
  std::string current_platform_;
  geometry::Kind current_kind_ = geometry::Kind::kPoint;
  int current_view_ = 0;
};

template <typename T>
void append(std::vector<T>& to, std::vector<T>&& from) {
  if (to.empty()) {
    to = std::move(from);
  } else {
    to.insert(to.end(), from.begin(), from.end());
    std::vector<T>().swap(from);
  }
}

// A view while merging files: its data, and which files hold which index range.
struct MergedView {
  PartialView view;
  std::string meta_file;
  struct Range {
    std::size_t file;
    std::uint64_t min, max;
  };
  std::vector<Range> ranges;
};

// The smallest index that occurs more than once, if any. Indices of a view are normally 0..n-1
// (shards are index ranges): a bitmap finds a repeat in one pass; sparse indices are sorted.
std::optional<std::uint64_t> first_duplicate(std::vector<std::uint64_t>& indices) {
  if (indices.empty()) return std::nullopt;
  const std::uint64_t top = *std::max_element(indices.begin(), indices.end());
  if (top < 8 * static_cast<std::uint64_t>(indices.size()) + (1u << 20)) {
    std::vector<bool> seen(top + 1);
    std::optional<std::uint64_t> dup;
    for (std::uint64_t i : indices) {
      if (seen[i] && (!dup || i < *dup)) dup = i;
      seen[i] = true;
    }
    return dup;
  }
  std::sort(indices.begin(), indices.end());
  const auto it = std::adjacent_find(indices.begin(), indices.end());
  if (it == indices.end()) return std::nullopt;
  return *it;
}

// The view groups: the views of a platform and kind with the same view_group, by orientation; they
// must differ in nothing else.
std::vector<ViewGroup> view_groups_of(const std::map<ViewKey, ViewData>& views,
                                      const std::string& records_dir) {
  std::vector<ViewGroup> groups;
  std::map<std::tuple<std::size_t, int, int>, std::vector<const ViewData*>> grouped;
  for (const auto& [key, data] : views) {
    grouped[{key.platform, static_cast<int>(key.kind), data.meta.view_group}].push_back(&data);
  }
  for (auto& [key, members] : grouped) {
    std::sort(members.begin(), members.end(), [](const ViewData* a, const ViewData* b) {
      return std::tie(a->meta.orientation, a->meta.view) <
             std::tie(b->meta.orientation, b->meta.view);
    });
    ViewGroup g;
    g.platform = std::get<0>(key);
    g.kind = static_cast<geometry::Kind>(std::get<1>(key));
    g.view_group = std::get<2>(key);
    g.label = view_group_label(g.view_group);
    g.views = members;
    for (const ViewData* v : members) {
      ViewMeta same = v->meta;
      same.view = g.meta().view;
      same.orientation = g.meta().orientation;
      const std::string diff = meta_difference(same, g.meta());
      if (!diff.empty()) {
        throw util::UserError(records_dir + ": views " + std::to_string(g.meta().view) +
                        " and " + std::to_string(v->meta.view) + " are both in view group " +
                        g.label + " but differ in more than orientation (view " +
                        std::to_string(v->meta.view) + " has " + diff + ")");
      }
    }
    groups.push_back(std::move(g));
  }
  return groups;
}

}  // namespace

RunRecords load_run_records(const std::string& run_dir, const LoadOptions& options) {
  std::error_code ec;
  if (!fs::is_directory(run_dir, ec)) {
    throw util::UserError(run_dir +
                    ": no such directory (expected a run directory written by "
                    "`renderaudit run`)");
  }
  const fs::path records_dir = rundir::run_folder::records(run_dir);
  if (!fs::is_directory(records_dir, ec)) {
    throw util::UserError(run_dir + ": no records directory (" + records_dir.string() +
                    "); is this a run directory written by `renderaudit run`?");
  }
  if (options.point_margin_px > 0 && options.experiment == nullptr)
    throw std::logic_error("load_run_records: point_margin_px needs the run's experiment");
  RunRecords run;
  run.run_dir = run_dir;
  run.point_margin_px = options.point_margin_px;
  for (const auto& e : fs::directory_iterator(records_dir)) {
    if (ra::rundir::is_records_file_name(e.path().filename().string()) && e.is_regular_file())
      run.files.push_back(e.path().string());
  }
  std::sort(run.files.begin(), run.files.end());
  if (run.files.empty()) {
    throw util::UserError(records_dir.string() +
                    ": no records files (*.csv.zst, *.csv); the run has not finished a shard yet");
  }

  // parse in parallel; keep each file's result so that merging follows the file order
  const MetricColumns& metric_cols = metric_columns();
  const std::size_t n_files = run.files.size();
  std::vector<FileChunk> chunks(n_files);
  util::run_in_parallel(n_files, options.jobs,
                  [&](std::size_t f) {
                    const std::string name =
                        fs::path(run.files[f]).lexically_relative(run_dir).string();
                    chunks[f] = FileParser(run.files[f], name, metric_cols, options).parse();
                  });

  // merge, checking that a view has the same parameters everywhere
  std::map<PartialKey, MergedView> merged;
  std::map<int, std::pair<ViewMeta, std::size_t>> view_meta;  // view -> parameters, file
  for (std::size_t f = 0; f < n_files; ++f) {
    run.record_count += chunks[f].records;
    run.points_within_margin += chunks[f].points_within_margin;
    append_conformance(run.conformance, std::move(chunks[f].conformance));
    if (chunks[f].seal)
      run.seals.emplace(fs::path(run.files[f]).filename().string(), std::move(*chunks[f].seal));
    for (auto& [key, part] : chunks[f].views) {
      const ViewMeta& meta = part.data.meta;
      auto [vm, first] = view_meta.try_emplace(meta.view, meta, f);
      if (!first) {
        const std::string diff = meta_difference(meta, vm->second.first);
        if (!diff.empty()) {
          throw util::UserError(run.files[f] + ":" + std::to_string(part.meta_line) + ": view " +
                          std::to_string(meta.view) + " has " + diff + " in " +
                          run.files[vm->second.second]);
        }
      }
      MergedView& m = merged[key];
      m.ranges.push_back({f, part.min_index, part.max_index});
      if (m.view.data.values.empty()) {
        m.view = std::move(part);
        continue;
      }
      ViewData& to = m.view.data;
      ViewData& from = part.data;
      for (std::size_t c = 0; c < to.counts.by_class.size(); ++c)
        to.counts.by_class[c] += from.counts.by_class[c];
      to.counts.invalid += from.counts.invalid;
      to.counts.crash += from.counts.crash;
      to.counts.timeout += from.counts.timeout;
      for (std::size_t mi = 0; mi < to.values.size(); ++mi) {
        append(to.values[mi], std::move(from.values[mi]));
        to.missing[mi] += from.missing[mi];
      }
      append(to.render_us_visible, std::move(from.render_us_visible));
      append(to.render_us_other, std::move(from.render_us_other));
      append(m.view.indices, std::move(part.indices));
    }
    chunks[f] = FileChunk();
  }

  finish_conformance(run.conformance);

  // no record counted twice
  for (auto& [key, m] : merged) {
    const std::optional<std::uint64_t> dup = first_duplicate(m.view.indices);
    if (dup) {
      std::string where;
      for (const auto& r : m.ranges) {
        if (r.min <= *dup && *dup <= r.max)
          where += (where.empty() ? "" : ", ") + run.files[r.file];
      }
      throw util::UserError("records of platform " + std::get<0>(key) + ", kind " +
                            kind_name(static_cast<geometry::Kind>(std::get<1>(key))) + ", view " +
                            std::to_string(std::get<2>(key)) + ", index " + std::to_string(*dup) +
                            " appear more than once (in " + where +
                            "); remove the duplicated records file");
    }
    std::vector<std::uint64_t>().swap(m.view.indices);
  }

  for (const auto& [key, m] : merged) run.platforms.push_back(std::get<0>(key));
  std::sort(run.platforms.begin(), run.platforms.end());
  run.platforms.erase(std::unique(run.platforms.begin(), run.platforms.end()), run.platforms.end());
  for (auto& [key, m] : merged) {
    const std::size_t p = static_cast<std::size_t>(
        std::lower_bound(run.platforms.begin(), run.platforms.end(), std::get<0>(key)) -
        run.platforms.begin());
    run.views.emplace(ViewKey{p, static_cast<geometry::Kind>(std::get<1>(key)), std::get<2>(key)},
                      std::move(m.view.data));
  }

  // every sample ascending (see ViewData::values)
  std::vector<std::vector<double>*> samples;
  for (auto& [key, data] : run.views) {
    for (auto& v : data.values) samples.push_back(&v);
    samples.push_back(&data.render_us_visible);
    samples.push_back(&data.render_us_other);
  }
  util::run_in_parallel(samples.size(), options.jobs,
                  [&](std::size_t i) { std::sort(samples[i]->begin(), samples[i]->end()); });

  run.groups = view_groups_of(run.views, records_dir.string());
  return run;
}

}  // namespace ra::analysis
