// The pieces that the paper's tables (paper_tables.h) share: the view-group row headers and
// notes, scales and units, pooled samples. Internal to analysis/: the table files include it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "analysis/run_records.h"
#include "stats/descriptive.h"
#include "stats/table_writer.h"

namespace ra::analysis::table_parts {

// "128" for a square window, "640x480" otherwise.
std::string window_text(const ViewMeta& m);
std::string join_ints(const std::vector<int>& v);
// The parameters of view group `g` of a kind, from the first platform that has it.
const ViewGroup* any_group(const RunRecords& run, geometry::Kind kind, int g);
// True when the groups differ in their clip planes (then the tables show them).
bool planes_vary(const RunRecords& run);
// Row-header columns of a per-view-group table, and the cells of one group.
void add_view_columns(stats::Table& t, bool planes);
void add_view_cells(std::vector<stats::TableCell>& row, const ViewGroup& g, bool planes);
// "View groups: A = views 1, 2 (FOV 30, window 128); ..."
std::string group_note(const RunRecords& run, geometry::Kind kind);
// "x1", "x10^3".
std::string scale_text(int exponent);
const char* unit_long(MetricUnit unit);
// The description of an ascending sample (every sample here is kept sorted), if it has values.
std::optional<stats::Description> describe_if_any(const std::vector<double>& ascending,
                                                  stats::QuantileDefinition q);
// All view groups of a platform and kind pooled.
std::vector<double> pooled_all(const RunRecords& run, std::size_t p, geometry::Kind kind,
                               std::size_t metric);

}  // namespace ra::analysis::table_parts
