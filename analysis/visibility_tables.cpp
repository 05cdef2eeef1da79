// The visibility counts of each kind (Tables 2, 5, 8; paper_tables.h) and their shares with
// binomial intervals.
#include "analysis/paper_tables.h"

#include <cmath>

#include "analysis/paper_table_parts.h"

namespace ra::analysis {

using namespace table_parts;
using stats::Description;
using stats::QuantileDefinition;

namespace {

// One row per platform and view group of `kind` (platform, view, then the cells `counts` adds
// from the group's visibility counts), a rule above each platform's first.
template <typename Counts>
void add_group_rows(const RunRecords& run, geometry::Kind kind, stats::Table& t,
                    const Counts& counts) {
  for (std::size_t p = 0; p < run.platforms.size(); ++p) {
    bool first = true;
    for (const ViewGroup* g : run.groups_of(p, kind)) {
      if (first) t.rules_before.push_back(t.rows.size());
      first = false;
      std::vector<stats::TableCell> row = {stats::text_cell(run.platforms[p]),
                                           stats::text_cell(g->label)};
      counts(row, g->counts());
      t.rows.push_back(std::move(row));
    }
  }
}

}  // namespace

// So that two platforms' (or the paper's) counts can be compared with their uncertainty.
stats::Table visibility_share_table(const RunRecords& run, geometry::Kind kind) {
  const int number = kind == geometry::Kind::kPoint ? 2 : kind == geometry::Kind::kLine ? 5 : 8;
  stats::Table t;
  t.file_stem = "table0" + std::to_string(number) + "s_" + kind_name(kind) + "_visibility_shares";
  t.title = "Table " + std::to_string(number) + "s (supplements Table " + std::to_string(number) +
            "): the share of " + kind_label_plural(kind) +
            " in each visibility category, percent of the view group's ok records, with "
            "Clopper-Pearson 95% intervals";
  bool multiple = kind == geometry::Kind::kPoint;
  for (const ViewGroup& g : run.groups)
    if (g.kind == kind) multiple = multiple || g.counts().by_class[4] > 0;
  t.columns = {{"Platform", stats::Align::kLeft},       {"View", stats::Align::kLeft},
               {"Records", stats::Align::kRight},       {"True visible", stats::Align::kRight},
               {"True invisible", stats::Align::kRight}, {"False visible", stats::Align::kRight},
               {"False invisible", stats::Align::kRight}};
  if (multiple) t.columns.push_back({"Multiple visible", stats::Align::kRight});
  const int classes = multiple ? 5 : 4;
  add_group_rows(run, kind, t, [&](std::vector<stats::TableCell>& row, const VisibilityCounts& c) {
    std::uint64_t ok = 0;
    for (std::uint64_t n : c.by_class) ok += n;
    row.push_back(stats::count_cell(ok));
    for (int v = 0; v < classes; ++v)
      row.push_back(stats::share_cell(c.by_class[static_cast<std::size_t>(v)], ok));
  });
  t.notes = {"Shares of the records with status ok; the interval is exact (Clopper-Pearson, "
             "stats/binomial_interval.h). CSV: the share alone.",
             group_note(run, kind)};
  return t;
}

stats::Table visibility_table(const RunRecords& run, geometry::Kind kind) {
  const int number = kind == geometry::Kind::kPoint ? 2 : kind == geometry::Kind::kLine ? 5 : 8;
  stats::Table t;
  t.file_stem = "table0" + std::to_string(number) + "_" + kind_name(kind) + "_visibility";
  t.title = "Table " + std::to_string(number) + " (mirrors the paper's Table " +
            std::to_string(number) + "): the counts of " + kind_label_plural(kind) +
            " rendered in each visibility category for each view group and platform; counts of "
            "records, unscaled";
  bool multiple = kind == geometry::Kind::kPoint;
  bool invalid = false, crash = false, timeout = false;
  for (const ViewGroup& g : run.groups) {
    if (g.kind != kind) continue;
    const VisibilityCounts c = g.counts();
    multiple = multiple || c.by_class[4] > 0;
    invalid = invalid || c.invalid > 0;
    crash = crash || c.crash > 0;
    timeout = timeout || c.timeout > 0;
  }
  t.columns = {{"Platform", stats::Align::kLeft},       {"View", stats::Align::kLeft},
               {"True visible", stats::Align::kRight},  {"True invisible", stats::Align::kRight},
               {"False visible", stats::Align::kRight}, {"False invisible", stats::Align::kRight}};
  if (multiple) t.columns.push_back({"Multiple visible", stats::Align::kRight});
  if (invalid) t.columns.push_back({"Invalid", stats::Align::kRight});
  if (crash) t.columns.push_back({"Crash", stats::Align::kRight});
  if (timeout) t.columns.push_back({"Timeout", stats::Align::kRight});
  add_group_rows(run, kind, t, [&](std::vector<stats::TableCell>& row, const VisibilityCounts& c) {
    for (int v = 0; v < 4; ++v)
      row.push_back(stats::count_cell(c.by_class[static_cast<std::size_t>(v)]));
    if (multiple) row.push_back(stats::count_cell(c.by_class[4]));
    if (invalid) row.push_back(stats::count_cell(c.invalid));
    if (crash) row.push_back(stats::count_cell(c.crash));
    if (timeout) row.push_back(stats::count_cell(c.timeout));
  });
  t.notes = {
      "Classes (paper section 3.4) count records with status ok; invalid, crash and "
      "timeout records are counted apart, in their own columns when there are any.",
      group_note(run, kind)};
  if (kind == geometry::Kind::kPoint && run.point_margin_px > 0) {
    t.notes.push_back(
        "The paper's point convention (--point-margin-px " +
        stats::format_significant(run.point_margin_px, 6) + "): " +
        std::to_string(run.points_within_margin) +
        " true-invisible points whose projection lies within that many pixels outside the window "
        "are counted false-invisible (docs/method.md, \"Where we differ from the paper\").");
  }
  if (kind != geometry::Kind::kPoint && multiple) {
    t.notes.push_back(
        "Multiple visible is shown because the records use it for this kind (the "
        "paper uses it for points only).");
  }
  return t;
}

}  // namespace ra::analysis
