// Loading a run directory's records into samples; see run_records.h.
//
// Speed: ra::read_records builds a Record per row with std::getline, substr and std::stod (about a
// microsecond per field); the analysis needs 14 of the 33 columns, so this reader splits each line
// into string views in place and converts only those with std::from_chars, reading files in blocks
// of 4 MiB on several threads. The schema still comes from metrics/records.h (records_header()).
#include "analysis/run_records.h"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <thread>
#include <tuple>

#include "util/errors.h"
#include "metrics/records.h"
#include "geometry/view.h"

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
  std::vector<double> all;
  all.reserve(n);
  for (const auto* p : parts) {
    const auto middle = static_cast<std::ptrdiff_t>(all.size());
    all.insert(all.end(), p->begin(), p->end());
    std::inplace_merge(all.begin(), all.begin() + middle, all.end());
  }
  return all;
}

void run_in_parallel(std::size_t count, unsigned jobs,
                     const std::function<void(std::size_t)>& task) {
  std::vector<std::exception_ptr> errors(count);
  std::atomic<std::size_t> next{0};
  const auto work = [&] {
    for (std::size_t i; (i = next.fetch_add(1)) < count;) {
      try {
        task(i);
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
  };
  unsigned threads = jobs ? jobs : std::max(1u, std::thread::hardware_concurrency());
  threads = static_cast<unsigned>(std::min<std::size_t>(threads, count));
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  for (const auto& e : errors) {
    if (e) std::rethrow_exception(e);
  }
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
  View v;
  v.group = view_group;
  return v.group_name();
}

namespace {

// Where the columns the analysis reads sit in a records row, found by name in records_header().
struct Layout {
  std::string header;
  std::size_t count = 0;
  std::size_t platform = 0, view = 0, view_group = 0, orientation = 0, fov = 0, width = 0,
              height = 0, near = 0, far = 0, kind = 0, index = 0, status = 0, visibility = 0,
              render_us = 0;
  std::array<std::vector<std::size_t>, kKindCount> metrics;
  std::vector<std::string> names;
};

Layout make_layout() {
  Layout l;
  l.header = records_header();
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = l.header.find(',', start);
    l.names.push_back(l.header.substr(start, comma == std::string::npos ? comma : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  l.count = l.names.size();
  const auto at = [&](std::string_view name) {
    const auto it = std::find(l.names.begin(), l.names.end(), name);
    if (it == l.names.end()) {
      throw std::logic_error("metrics/records.h has no column '" + std::string(name) +
                             "': the analysis stage must follow the schema change");
    }
    return static_cast<std::size_t>(it - l.names.begin());
  };
  l.platform = at("platform");
  l.view = at("view");
  l.view_group = at("view_group");
  l.orientation = at("orientation");
  l.fov = at("fov_deg");
  l.width = at("width");
  l.height = at("height");
  l.near = at("near");
  l.far = at("far");
  l.kind = at("kind");
  l.index = at("index");
  l.status = at("status");
  l.visibility = at("visibility");
  l.render_us = at("render_us");
  for (PrimitiveKind k : kAllKinds) {
    for (const MetricSpec& m : kind_metrics(k))
      l.metrics[static_cast<std::size_t>(k)].push_back(at(m.column));
  }
  return l;
}

const Layout& layout() {
  static const Layout l = make_layout();
  return l;
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
};

// Difference between two views' parameters, "" when equal.
std::string meta_difference(const ViewMeta& here, const ViewMeta& there) {
  const auto num = [](double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return std::string(buf);
  };
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

class FileParser {
 public:
  FileParser(const std::string& path, const Layout& layout) : path_(path), l_(layout) {
    for (int s = 0; s < 4; ++s) status_names_[s] = status_name(static_cast<CaseStatus>(s));
    for (int v = 0; v < 5; ++v) visibility_names_[v] = visibility_name(static_cast<Visibility>(v));
    fields_.resize(l_.count);
    meta_columns_ = {l_.view_group, l_.orientation, l_.fov, l_.width, l_.height, l_.near, l_.far};
  }

  FileChunk parse() {
    std::ifstream in(path_, std::ios::binary);
    if (!in) throw UserError(path_ + ": cannot read records file");
    std::vector<char> block(std::size_t{4} << 20);
    std::string carry;  // an incomplete line from the previous block
    while (in) {
      in.read(block.data(), static_cast<std::streamsize>(block.size()));
      const std::size_t n = static_cast<std::size_t>(in.gcount());
      if (n == 0) break;
      std::size_t start = 0;
      for (;;) {
        const void* found = std::memchr(block.data() + start, '\n', n - start);
        if (!found) break;
        const std::size_t end =
            static_cast<std::size_t>(static_cast<const char*>(found) - block.data());
        if (carry.empty()) {
          line(std::string_view(block.data() + start, end - start));
        } else {
          carry.append(block.data() + start, end - start);
          line(carry);
          carry.clear();
        }
        start = end + 1;
      }
      carry.append(block.data() + start, n - start);
    }
    if (in.bad()) throw UserError(path_ + ": read error");
    if (!carry.empty()) line(carry);
    if (line_no_ == 0) bad_header();
    return std::move(chunk_);
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    throw UserError(path_ + ":" + std::to_string(line_no_) + ": " + why);
  }
  [[noreturn]] void bad_header() const {
    throw UserError(path_ + ":1: unexpected records header (schema version " +
                    std::to_string(kRecordsSchemaVersion) + " expects: " + l_.header + ")");
  }

  template <typename Int>
  Int integer(std::size_t column) const {
    const std::string_view f = fields_[column];
    Int v{};
    const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
    if (ec != std::errc() || end != f.data() + f.size() || f.empty()) {
      fail("column '" + l_.names[column] + "': '" + std::string(f) + "' is not an integer");
    }
    return v;
  }

  // A finite number, or nullopt for an empty cell.
  std::optional<double> number(std::size_t column) const {
    const std::string_view f = fields_[column];
    if (f.empty()) return std::nullopt;
    double v = 0;
    const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
    if (ec != std::errc() || end != f.data() + f.size() || !std::isfinite(v)) {
      fail("column '" + l_.names[column] + "': '" + std::string(f) + "' is not a finite number");
    }
    return v;
  }

  double required_number(std::size_t column) const {
    const std::optional<double> v = number(column);
    if (!v) fail("column '" + l_.names[column] + "' is empty");
    return *v;
  }

  void line(std::string_view text) {
    ++line_no_;
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    if (line_no_ == 1) {
      if (text != l_.header) bad_header();
      return;
    }
    if (!text.empty() && text.front() == '#') return;  // the seal of a shard file (shard_file.h)
    // split into fields_ without copying
    std::size_t n = 0;
    std::size_t start = 0;
    for (;;) {
      const std::size_t comma = text.find(',', start);
      if (n < fields_.size()) {
        fields_[n] = text.substr(start, comma == std::string_view::npos ? comma : comma - start);
      }
      ++n;
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    if (n != l_.count) {
      fail("expected " + std::to_string(l_.count) + " fields, found " + std::to_string(n));
    }
    ++chunk_.records;

    const std::string_view platform = fields_[l_.platform];
    if (platform.empty()) fail("column 'platform' is empty");
    const std::optional<PrimitiveKind> kind = parse_kind(fields_[l_.kind]);
    if (!kind) {
      fail("unknown kind '" + std::string(fields_[l_.kind]) + "' (allowed: point, line, triangle)");
    }
    const int view = integer<int>(l_.view);
    if (view < 1) fail("column 'view': " + std::to_string(view) + " is not a view number (>= 1)");

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
        current_->data.meta = read_meta(view);
        current_->meta_line = line_no_;
        for (std::size_t c : meta_columns_) current_->meta_text.emplace_back(fields_[c]);
      } else {
        check_meta(view);
      }
    } else {
      check_meta(view);
    }
    PartialView& pv = *current_;

    const std::uint64_t index = integer<std::uint64_t>(l_.index);
    pv.indices.push_back(index);
    pv.min_index = std::min(pv.min_index, index);
    pv.max_index = std::max(pv.max_index, index);

    const std::string_view status = fields_[l_.status];
    int s = 0;
    while (s < 4 && status != status_names_[s]) ++s;
    if (s == 4)
      fail("unknown status '" + std::string(status) + "' (allowed: ok, invalid, crash, timeout)");
    const std::string_view visibility = fields_[l_.visibility];
    int v = 0;
    while (v < 5 && visibility != visibility_names_[v]) ++v;
    if (v == 5) fail("unknown visibility '" + std::string(visibility) + "'");

    VisibilityCounts& counts = pv.data.counts;
    switch (static_cast<CaseStatus>(s)) {
      case CaseStatus::kOk:
        break;
      case CaseStatus::kInvalid:
        ++counts.invalid;
        return;
      case CaseStatus::kCrash:
        ++counts.crash;
        return;
      case CaseStatus::kTimeout:
        ++counts.timeout;
        return;
    }
    ++counts.by_class[static_cast<std::size_t>(v)];
    const bool visible = static_cast<Visibility>(v) == Visibility::kTrueVisible;
    if (const std::optional<double> t = number(l_.render_us)) {
      (visible ? pv.data.render_us_visible : pv.data.render_us_other).push_back(*t);
    }
    if (!visible) return;
    const std::vector<std::size_t>& columns = l_.metrics[static_cast<std::size_t>(*kind)];
    for (std::size_t m = 0; m < columns.size(); ++m) {
      if (const std::optional<double> x = number(columns[m])) {
        pv.data.values[m].push_back(*x);
      } else {
        ++pv.data.missing[m];
      }
    }
  }

  ViewMeta read_meta(int view) const {
    ViewMeta m;
    m.view = view;
    m.view_group = integer<int>(l_.view_group);
    m.orientation = integer<int>(l_.orientation);
    m.fov_deg = required_number(l_.fov);
    m.width = integer<int>(l_.width);
    m.height = integer<int>(l_.height);
    m.near = required_number(l_.near);
    m.far = required_number(l_.far);
    if (m.view_group < 0) fail("column 'view_group': " + std::to_string(m.view_group) + " < 0");
    if (m.width < 1 || m.height < 1) fail("the window must be at least 1x1 pixels");
    return m;
  }

  void check_meta(int view) const {
    // the same text as the first record of the view: the same parameters (the usual case, and
    // cheaper than converting 7 numbers per record); otherwise compare the numbers
    bool same_text = true;
    for (std::size_t i = 0; i < meta_columns_.size() && same_text; ++i) {
      same_text = fields_[meta_columns_[i]] == current_->meta_text[i];
    }
    if (same_text) return;
    const std::string diff = meta_difference(read_meta(view), current_->data.meta);
    if (!diff.empty()) {
      fail("view " + std::to_string(view) + " (" + current_platform_ + ", " +
           kind_name(current_kind_) + ") has " + diff + " on line " +
           std::to_string(current_->meta_line));
    }
  }

  const std::string& path_;
  const Layout& l_;
  std::array<std::string_view, 4> status_names_;
  std::array<std::string_view, 5> visibility_names_;
  std::vector<std::string_view> fields_;
  std::vector<std::size_t> meta_columns_;  // the columns of a view's parameters
  std::int64_t line_no_ = 0;
  FileChunk chunk_;
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

}  // namespace

RunRecords load_run_records(const std::string& run_dir, const LoadOptions& options) {
  std::error_code ec;
  if (!fs::is_directory(run_dir, ec)) {
    throw UserError(run_dir +
                    ": no such directory (expected a run directory written by "
                    "`renderaudit run`)");
  }
  const fs::path records_dir = fs::path(run_dir) / "records";
  if (!fs::is_directory(records_dir, ec)) {
    throw UserError(run_dir + ": no records directory (" + records_dir.string() +
                    "); is this a run directory written by `renderaudit run`?");
  }
  RunRecords run;
  run.run_dir = run_dir;
  for (const auto& e : fs::directory_iterator(records_dir)) {
    if (e.path().extension() == ".csv" && e.is_regular_file())
      run.files.push_back(e.path().string());
  }
  std::sort(run.files.begin(), run.files.end());
  if (run.files.empty()) {
    throw UserError(records_dir.string() +
                    ": no records files (*.csv); the run has not finished a shard yet");
  }

  // parse in parallel; keep each file's result so that merging follows the file order
  const Layout& l = layout();
  const std::size_t n_files = run.files.size();
  std::vector<FileChunk> chunks(n_files);
  run_in_parallel(n_files, options.jobs,
                  [&](std::size_t f) { chunks[f] = FileParser(run.files[f], l).parse(); });

  // merge, checking that a view has the same parameters everywhere
  std::map<PartialKey, MergedView> merged;
  std::map<int, std::pair<ViewMeta, std::size_t>> view_meta;  // view -> parameters, file
  for (std::size_t f = 0; f < n_files; ++f) {
    run.record_count += chunks[f].records;
    for (auto& [key, part] : chunks[f].views) {
      const ViewMeta& meta = part.data.meta;
      auto [vm, first] = view_meta.try_emplace(meta.view, meta, f);
      if (!first) {
        const std::string diff = meta_difference(meta, vm->second.first);
        if (!diff.empty()) {
          throw UserError(run.files[f] + ":" + std::to_string(part.meta_line) + ": view " +
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

  // no record counted twice
  for (auto& [key, m] : merged) {
    const std::optional<std::uint64_t> dup = first_duplicate(m.view.indices);
    if (dup) {
      std::string where;
      for (const auto& r : m.ranges) {
        if (r.min <= *dup && *dup <= r.max)
          where += (where.empty() ? "" : ", ") + run.files[r.file];
      }
      throw UserError("records of platform " + std::get<0>(key) + ", kind " +
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
  run_in_parallel(samples.size(), options.jobs,
                  [&](std::size_t i) { std::sort(samples[i]->begin(), samples[i]->end()); });

  // view groups: the views of a platform and kind with the same view_group
  std::map<std::tuple<std::size_t, int, int>, std::vector<const ViewData*>> grouped;
  for (const auto& [key, data] : run.views) {
    grouped[{key.platform, static_cast<int>(key.kind), data.meta.view_group}].push_back(&data);
  }
  for (auto& [key, views] : grouped) {
    std::sort(views.begin(), views.end(), [](const ViewData* a, const ViewData* b) {
      return std::tie(a->meta.orientation, a->meta.view) <
             std::tie(b->meta.orientation, b->meta.view);
    });
    ViewGroup g;
    g.platform = std::get<0>(key);
    g.kind = static_cast<PrimitiveKind>(std::get<1>(key));
    g.view_group = std::get<2>(key);
    g.label = view_group_label(g.view_group);
    g.views = views;
    for (const ViewData* v : views) {
      ViewMeta same = v->meta;
      same.view = g.meta().view;
      same.orientation = g.meta().orientation;
      const std::string diff = meta_difference(same, g.meta());
      if (!diff.empty()) {
        throw UserError(records_dir.string() + ": views " + std::to_string(g.meta().view) +
                        " and " + std::to_string(v->meta.view) + " are both in view group " +
                        g.label + " but differ in more than orientation (view " +
                        std::to_string(v->meta.view) + " has " + diff + ")");
      }
    }
    run.groups.push_back(std::move(g));
  }
  return run;
}

}  // namespace ra::analysis
