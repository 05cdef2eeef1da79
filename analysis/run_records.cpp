// Loading a run directory's records into samples; see run_records.h.
//
// Speed: the analysis needs 14 of the 37 columns, so each row is read with rundir/records_reader.h
// (split in place, only those cells converted) and files are parsed on several threads.
#include "analysis/run_records.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <tuple>

#include "rundir/records_format.h"
#include "util/errors.h"
#include "metrics/records.h"
#include "rundir/records_reader.h"
#include "geometry/view.h"
#include "metrics/point_metrics.h"
#include "util/cell_text.h"

namespace fs = std::filesystem;

namespace ra::analysis {

const char* kind_label_plural(PrimitiveKind kind) {
  switch (kind) {
    case PrimitiveKind::kPoint:
      return "points";
    case PrimitiveKind::kLine:
      return "line segments";
    case PrimitiveKind::kTriangle:
      return "triangles";
  }
  return "unknown";
}

std::optional<PrimitiveKind> parse_kind(std::string_view name) {
  for (PrimitiveKind k : kAllKinds) {
    if (name == kind_name(k)) return k;
  }
  return std::nullopt;
}

const char* unit_name(MetricUnit unit) {
  switch (unit) {
    case MetricUnit::kPixels:
      return "px";
    case MetricUnit::kSquarePixels:
      return "px^2";
    case MetricUnit::kNormalizedLength:
      return "sqrt(W*H) units";
    case MetricUnit::kNormalizedArea:
      return "W*H units";
  }
  return "unknown";
}

const std::vector<MetricSpec>& kind_metrics(PrimitiveKind kind) {
  using K = PrimitiveKind;
  using U = MetricUnit;
  static const std::array<std::vector<MetricSpec>, kKindCount> metrics = {
      std::vector<MetricSpec>{
          {"pe", K::kPoint, "PE", "point rendering error", U::kPixels},
          {"pe_norm", K::kPoint, "PEnorm", "normalized point rendering error",
           U::kNormalizedLength},
      },
      std::vector<MetricSpec>{
          {"lse_s_norm", K::kLine, "LSEs-norm", "normalized signed line segment rendering error",
           U::kNormalizedLength},
          {"lse_u_norm", K::kLine, "LSEu-norm", "normalized unsigned line segment rendering error",
           U::kNormalizedLength},
          {"lse_s", K::kLine, "LSEs", "signed line segment rendering error", U::kPixels},
          {"lse_u", K::kLine, "LSEu", "unsigned line segment rendering error", U::kPixels},
      },
      std::vector<MetricSpec>{
          {"te_s_norm", K::kTriangle, "TEs-norm", "normalized signed triangle rendering error",
           U::kNormalizedArea},
          {"te_u_norm", K::kTriangle, "TEu-norm", "normalized unsigned triangle rendering error",
           U::kNormalizedArea},
          {"te_s", K::kTriangle, "TEs", "signed triangle rendering error", U::kSquarePixels},
          {"te_u", K::kTriangle, "TEu", "unsigned triangle rendering error", U::kSquarePixels},
          {"te_u_edge_norm", K::kTriangle, "TEu-edge-norm",
           "unsigned triangle rendering error per pixel of visible edge", U::kPixels},
      },
  };
  return metrics[static_cast<std::size_t>(kind)];
}

std::size_t metric_index(PrimitiveKind kind, std::string_view column) {
  const auto& metrics = kind_metrics(kind);
  for (std::size_t m = 0; m < metrics.size(); ++m) {
    if (column == metrics[m].column) return m;
  }
  throw std::logic_error("metric_index: '" + std::string(column) + "' is not a metric of " +
                         kind_name(kind));
}

std::uint64_t VisibilityCounts::total() const {
  std::uint64_t n = invalid + crash + timeout;
  for (std::uint64_t c : by_class) n += c;
  return n;
}

bool ViewKey::operator<(const ViewKey& o) const {
  return std::tie(platform, kind, view) < std::tie(o.platform, o.kind, o.view);
}

std::size_t ViewGroup::count(std::size_t metric) const {
  std::size_t n = 0;
  for (const ViewData* v : views) n += v->values[metric].size();
  return n;
}

std::vector<double> ViewGroup::pooled(std::size_t metric) const {
  std::vector<const std::vector<double>*> parts;
  for (const ViewData* v : views) parts.push_back(&v->values[metric]);
  return merge_sorted(parts);
}

stats::Description describe_sorted(const std::vector<double>& ascending,
                                   stats::QuantileDefinition definition) {
  if (ascending.empty() || !std::is_sorted(ascending.begin(), ascending.end())) {
    throw std::logic_error("describe_sorted: the sample is empty or not ascending");
  }
  const stats::MeanVariance mv = stats::mean_and_variance(ascending);
  stats::Description d;
  d.n = ascending.size();
  d.mean = mv.mean;
  d.sd = mv.sd;
  d.median = stats::quantile_sorted(ascending, 0.5, definition);
  d.q1 = stats::quantile_sorted(ascending, 0.25, definition);
  d.q3 = stats::quantile_sorted(ascending, 0.75, definition);
  d.iqr = d.q3 - d.q1;
  d.min = ascending.front();
  d.max = ascending.back();
  return d;
}

std::vector<double> merge_sorted(const std::vector<const std::vector<double>*>& parts) {
  std::size_t n = 0;
  for (const auto* p : parts) n += p->size();
  // the parts side by side, then neighbouring runs merged pairwise, pass by pass: log2(k) passes
  // over the data instead of k
  std::vector<double> all;
  all.reserve(n);
  std::vector<std::size_t> ends;  // where each run ends
  for (const auto* p : parts) {
    if (p->empty()) continue;
    all.insert(all.end(), p->begin(), p->end());
    ends.push_back(all.size());
  }
  std::vector<double> merged;
  if (ends.size() > 1) merged.resize(all.size());
  while (ends.size() > 1) {
    std::vector<std::size_t> merged_ends;
    std::size_t begin = 0;
    for (std::size_t r = 0; r < ends.size(); r += 2) {
      const std::size_t middle = ends[r];
      const std::size_t end = r + 1 < ends.size() ? ends[r + 1] : middle;
      std::merge(all.begin() + std::ptrdiff_t(begin), all.begin() + std::ptrdiff_t(middle),
                 all.begin() + std::ptrdiff_t(middle), all.begin() + std::ptrdiff_t(end),
                 merged.begin() + std::ptrdiff_t(begin));
      merged_ends.push_back(end);
      begin = end;
    }
    all.swap(merged);
    ends = std::move(merged_ends);
  }
  return all;
}

VisibilityCounts ViewGroup::counts() const {
  VisibilityCounts sum;
  for (const ViewData* v : views) {
    for (std::size_t c = 0; c < sum.by_class.size(); ++c) sum.by_class[c] += v->counts.by_class[c];
    sum.invalid += v->counts.invalid;
    sum.crash += v->counts.crash;
    sum.timeout += v->counts.timeout;
  }
  return sum;
}

std::vector<int> ViewGroup::view_numbers() const {
  std::vector<int> numbers;
  for (const ViewData* v : views) numbers.push_back(v->meta.view);
  return numbers;
}

std::vector<PrimitiveKind> RunRecords::kinds() const {
  std::vector<PrimitiveKind> present;
  for (PrimitiveKind k : kAllKinds) {
    for (const auto& [key, data] : views) {
      if (key.kind == k) {
        present.push_back(k);
        break;
      }
    }
  }
  return present;
}

std::vector<const ViewGroup*> RunRecords::groups_of(std::size_t platform,
                                                    PrimitiveKind kind) const {
  std::vector<const ViewGroup*> out;
  for (const ViewGroup& g : groups) {
    if (g.platform == platform && g.kind == kind) out.push_back(&g);
  }
  return out;
}

const ViewGroup* RunRecords::find_group(std::size_t platform, PrimitiveKind kind,
                                        int view_group) const {
  for (const ViewGroup& g : groups) {
    if (g.platform == platform && g.kind == kind && g.view_group == view_group) return &g;
  }
  return nullptr;
}

std::vector<int> RunRecords::view_groups(PrimitiveKind kind) const {
  std::vector<int> numbers;
  for (const ViewGroup& g : groups) {
    if (g.kind == kind) numbers.push_back(g.view_group);
  }
  std::sort(numbers.begin(), numbers.end());
  numbers.erase(std::unique(numbers.begin(), numbers.end()), numbers.end());
  return numbers;
}

std::string view_group_label(int view_group) {
  geometry::View v;
  v.group = view_group;
  return v.group_name();
}

namespace {

// The records column of each metric of each kind (kind_metrics names them).
using MetricColumns = std::array<std::vector<metrics::RecordColumn>, kKindCount>;

MetricColumns make_metric_columns() {
  MetricColumns columns;
  for (PrimitiveKind k : kAllKinds) {
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
    const std::optional<PrimitiveKind> kind = parse_kind(row.cell(metrics::RecordColumn::kKind));
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
  metrics::Visibility paper_point_class(PrimitiveKind kind, int view, std::uint64_t index,
                               metrics::Visibility visibility) {
    if (options_.point_margin_px <= 0 || kind != PrimitiveKind::kPoint ||
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
  PrimitiveKind current_kind_ = PrimitiveKind::kPoint;
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
    g.kind = static_cast<PrimitiveKind>(std::get<1>(key));
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
  const fs::path records_dir = fs::path(run_dir) / "records";
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
                      kind_name(static_cast<PrimitiveKind>(std::get<1>(key))) + ", view " +
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
    run.views.emplace(ViewKey{p, static_cast<PrimitiveKind>(std::get<1>(key)), std::get<2>(key)},
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

const char* const kVulkanRenderTimeNote =
    "On a Vulkan platform (vk-*) render_us is the CPU time of recording the primitive's commands, "
    "submitting them and waiting for their fence (batches share one submission as GL's share one "
    "glFinish); copying the pixels back is a submission of its own, outside it.";

bool is_vulkan_platform(const std::string& platform) { return platform.rfind("vk-", 0) == 0; }

}  // namespace ra::analysis
