// What a run's records are as samples: the metrics of each kind, view groups and their pooled,
// sorted samples; see run_records.h. Loading them: run_records_load.cpp.
#include "analysis/run_records.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <tuple>

#include "rundir/records_format.h"
#include "util/errors.h"
#include "metrics/records.h"
#include "rundir/records_reader.h"
#include "geometry/view.h"
#include "metrics/point_metrics.h"
#include "util/cell_text.h"

namespace ra::analysis {

const char* kind_label_plural(geometry::Kind kind) {
  switch (kind) {
    case geometry::Kind::kPoint:
      return "points";
    case geometry::Kind::kLine:
      return "line segments";
    case geometry::Kind::kTriangle:
      return "triangles";
  }
  return "unknown";
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

const std::vector<MetricSpec>& kind_metrics(geometry::Kind kind) {
  using K = geometry::Kind;
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

std::size_t metric_index(geometry::Kind kind, std::string_view column) {
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

std::vector<geometry::Kind> RunRecords::kinds() const {
  std::vector<geometry::Kind> present;
  for (geometry::Kind k : kAllKinds) {
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
                                                    geometry::Kind kind) const {
  std::vector<const ViewGroup*> out;
  for (const ViewGroup& g : groups) {
    if (g.platform == platform && g.kind == kind) out.push_back(&g);
  }
  return out;
}

const ViewGroup* RunRecords::find_group(std::size_t platform, geometry::Kind kind,
                                        int view_group) const {
  for (const ViewGroup& g : groups) {
    if (g.platform == platform && g.kind == kind && g.view_group == view_group) return &g;
  }
  return nullptr;
}

std::vector<int> RunRecords::view_groups(geometry::Kind kind) const {
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

const char* const kVulkanRenderTimeNote =
    "On a Vulkan platform (vk-*) on the host's clock render_us is the CPU time of recording the "
    "primitive's commands, submitting them and waiting for their fence (batches share one "
    "submission as GL's share one glFinish); copying the pixels back is a submission of its own, "
    "outside it.";

const char* const kDeviceClockNote =
    "Where a GPU's driver times each draw itself (records column clock = device: egl-device, "
    "vk-device), render_us is the device's time around the primitive's own draw, batch or not, "
    "and the host's share of the submission and wait is the column host_us.";

bool is_vulkan_platform(const std::string& platform) { return platform.rfind("vk-", 0) == 0; }

}  // namespace ra::analysis
