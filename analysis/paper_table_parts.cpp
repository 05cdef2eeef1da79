// The pieces the paper's tables share; see paper_table_parts.h.
#include "analysis/paper_table_parts.h"

#include <cstdio>

#include "util/number_text.h"

namespace ra::analysis::table_parts {

using stats::Description;
using stats::QuantileDefinition;

std::string window_text(const ViewMeta& m) {
  return m.width == m.height ? std::to_string(m.width)
                             : std::to_string(m.width) + "x" + std::to_string(m.height);
}

std::string join_ints(const std::vector<int>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + std::to_string(v[i]);
  return s;
}

// The parameters of view group `g` of a kind, from the first platform that has it.
const ViewGroup* any_group(const RunRecords& run, geometry::Kind kind, int g) {
  for (std::size_t p = 0; p < run.platforms.size(); ++p) {
    if (const ViewGroup* group = run.find_group(p, kind, g)) return group;
  }
  return nullptr;
}

// True when the groups of `kinds` differ in their clip planes (then the tables show them).
bool planes_vary(const RunRecords& run) {
  for (const ViewGroup& g : run.groups) {
    if (g.meta().near != run.groups.front().meta().near ||
        g.meta().far != run.groups.front().meta().far) {
      return true;
    }
  }
  return false;
}

// Row-header columns of a per-view-group table.
void add_view_columns(stats::Table& t, bool planes) {
  t.columns.push_back({"View", stats::Align::kLeft});
  t.columns.push_back({"FOV", stats::Align::kRight});
  t.columns.push_back({"Win Size", stats::Align::kRight});
  if (planes) {
    t.columns.push_back({"Near", stats::Align::kRight});
    t.columns.push_back({"Far", stats::Align::kRight});
  }
}

void add_view_cells(std::vector<stats::TableCell>& row, const ViewGroup& g, bool planes) {
  row.push_back(stats::text_cell(g.label));
  row.push_back(stats::text_cell(util::significant(g.meta().fov_deg, 6)));
  row.push_back(stats::text_cell(window_text(g.meta())));
  if (planes) {
    row.push_back(stats::text_cell(util::significant(g.meta().near, 6)));
    row.push_back(stats::text_cell(util::significant(g.meta().far, 6)));
  }
}

// "View groups: A = views 1, 2 (FOV 30, window 128); ..."
std::string group_note(const RunRecords& run, geometry::Kind kind) {
  std::string s = "View groups pool the views that differ only by camera orientation: ";
  bool first = true;
  for (int g : run.view_groups(kind)) {
    const ViewGroup* group = any_group(run, kind, g);
    s += (first ? "" : "; ") + group->label + " = views " + join_ints(group->view_numbers()) +
         " (FOV " + util::significant(group->meta().fov_deg, 6) + ", window " + window_text(group->meta()) + ")";
    first = false;
  }
  return s + " (see view_equivalence.md).";
}

std::string scale_text(int exponent) {
  return exponent == 0 ? "x1" : "x10^" + std::to_string(exponent);
}

const char* unit_long(MetricUnit unit) {
  switch (unit) {
    case MetricUnit::kPixels:
      return "pixels";
    case MetricUnit::kSquarePixels:
      return "pixels^2";
    case MetricUnit::kNormalizedLength:
      return "normalized window units (length / sqrt(W*H))";
    case MetricUnit::kNormalizedArea:
      return "normalized window units (area / (W*H))";
  }
  return "unknown";
}

// The description of an ascending sample (every sample here is kept sorted), if it has values.
std::optional<Description> describe_if_any(const std::vector<double>& ascending,
                                           QuantileDefinition q) {
  if (ascending.empty()) return std::nullopt;
  return describe_sorted(ascending, q);
}

// All view groups of a platform and kind pooled.
std::vector<double> pooled_all(const RunRecords& run, std::size_t p, geometry::Kind kind,
                               std::size_t metric) {
  std::vector<const std::vector<double>*> parts;
  for (const ViewGroup* g : run.groups_of(p, kind)) {
    for (const ViewData* v : g->views) parts.push_back(&v->values[metric]);
  }
  return merge_sorted(parts);
}

}  // namespace ra::analysis::table_parts
