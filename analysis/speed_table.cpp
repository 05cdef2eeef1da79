// Render time beside error (paper_tables.h): median and IQR of render_us and of each kind's
// headline error by platform, kind and view group.
#include "analysis/paper_tables.h"

#include <cmath>

#include "analysis/paper_table_parts.h"
#include "metrics/headline_metric.h"
#include "util/number_text.h"

namespace ra::analysis {

using namespace table_parts;
using stats::Description;
using stats::QuantileDefinition;

stats::Table speed_table(const RunRecords& run, const TableOptions& options) {
  stats::Table t;
  t.file_stem = "speed";
  t.title =
      "Render time beside error (not in the paper): median and IQR of render_us (CPU "
      "microseconds of draw + glFinish) and of each kind's headline error (PE px, LSEu px, "
      "TEu px^2), by platform, kind and view group; quartiles " +
      quantile_label(options.quantiles);
  t.columns = {{"Platform", stats::Align::kLeft},
               {"Kind", stats::Align::kLeft},
               {"View", stats::Align::kLeft},
               {"FOV", stats::Align::kRight},
               {"Win Size", stats::Align::kRight},
               {"Cases", stats::Align::kRight},
               {"Median us", stats::Align::kRight},
               {"IQR us", stats::Align::kRight},
               {"True visible", stats::Align::kRight},
               {"Median us (visible)", stats::Align::kRight},
               {"IQR us (visible)", stats::Align::kRight},
               {"Error", stats::Align::kLeft},
               {"Median error", stats::Align::kRight},
               {"IQR error", stats::Align::kRight}};

  struct Row {
    std::size_t platform;
    geometry::Kind kind;
    const ViewGroup* group;  // nullptr: all groups pooled
  };
  std::vector<Row> rows;
  for (std::size_t p = 0; p < run.platforms.size(); ++p) {
    for (geometry::Kind k : run.kinds()) {
      const auto groups = run.groups_of(p, k);
      if (groups.empty()) continue;
      for (const ViewGroup* g : groups) rows.push_back({p, k, g});
      rows.push_back({p, k, nullptr});
    }
  }
  struct Computed {
    std::optional<Description> all, visible, error;
  };
  std::vector<Computed> computed(rows.size());
  util::run_in_parallel(rows.size(), options.jobs, [&](std::size_t i) {
    const Row& r = rows[i];
    const std::size_t metric = metric_index(r.kind, metrics::headline_column(r.kind));
    std::vector<const std::vector<double>*> all, visible, error;
    for (const ViewGroup* g : run.groups_of(r.platform, r.kind)) {
      if (r.group && g != r.group) continue;
      for (const ViewData* view : g->views) {
        all.push_back(&view->render_us_visible);
        all.push_back(&view->render_us_other);
        visible.push_back(&view->render_us_visible);
        error.push_back(&view->values[metric]);
      }
    }
    computed[i] = {describe_if_any(merge_sorted(all), options.quantiles),
                   describe_if_any(merge_sorted(visible), options.quantiles),
                   describe_if_any(merge_sorted(error), options.quantiles)};
  });
  const auto pair = [](std::vector<stats::TableCell>& row, const std::optional<Description>& d,
                       bool with_n, int decimals) {
    if (with_n) row.push_back(stats::count_cell(d ? d->n : 0));
    if (d) {
      row.push_back(decimals >= 0 ? stats::number_cell(d->median, decimals)
                                  : stats::significant_cell(d->median, 5));
      row.push_back(decimals >= 0 ? stats::number_cell(d->iqr, decimals) : stats::significant_cell(d->iqr, 5));
    } else {
      row.push_back(stats::text_cell("no data"));
      row.push_back(stats::text_cell("no data"));
    }
  };
  std::size_t last_platform = SIZE_MAX;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    if (r.platform != last_platform) t.rules_before.push_back(t.rows.size());
    last_platform = r.platform;
    std::vector<stats::TableCell> row = {stats::text_cell(run.platforms[r.platform]),
                                  stats::text_cell(kind_name(r.kind))};
    if (r.group) {
      row.push_back(stats::text_cell(r.group->label));
      row.push_back(stats::text_cell(util::significant(r.group->meta().fov_deg, 6)));
      row.push_back(stats::text_cell(window_text(r.group->meta())));
    } else {
      row.push_back(stats::text_cell("all"));
      row.push_back(stats::text_cell(""));
      row.push_back(stats::text_cell(""));
    }
    pair(row, computed[i].all, true, 2);
    pair(row, computed[i].visible, true, 2);
    const std::size_t metric = metric_index(r.kind, metrics::headline_column(r.kind));
    const MetricSpec& spec = kind_metrics(r.kind)[metric];
    row.push_back(stats::text_cell(std::string(spec.symbol) + " (" + unit_name(spec.unit) + ")"));
    // the decimals of the paper's non-normalized tables: PE 5 (Table 3), LSEu 4, TEu 3
    pair(row, computed[i].error, false,
         r.kind == geometry::Kind::kPoint  ? 5
         : r.kind == geometry::Kind::kLine ? 4
                                           : 3);
    t.rows.push_back(std::move(row));
  }
  t.notes = {
      "Cases: records with status ok and a render time; True visible: those of them that "
      "are true-visible (the error is measured on these).",
      "render_us is the CPU time of a primitive's draw call and glFinish, measured by the "
      "runner: alone for a large primitive, an equal share of one glFinish for small ones drawn "
      "in a batch (records column batch_size); on an antialiased platform it includes the "
      "resolve of the multisample buffer. It depends on the machine and its load, unlike the "
      "errors.",
      kDeviceClockNote};
  if (std::any_of(run.platforms.begin(), run.platforms.end(), is_vulkan_platform))
    t.notes.push_back(kVulkanRenderTimeNote);
  return t;
}

}  // namespace ra::analysis
