// The paper's tables from a run's records; see paper_tables.h.
#include "analysis/paper_tables.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace ra::analysis {
namespace {

using stats::Description;
using stats::QuantileDefinition;

std::string fmt_g(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

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
const ViewGroup* any_group(const RunRecords& run, PrimitiveKind kind, int g) {
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
  row.push_back(stats::text_cell(fmt_g(g.meta().fov_deg)));
  row.push_back(stats::text_cell(window_text(g.meta())));
  if (planes) {
    row.push_back(stats::text_cell(fmt_g(g.meta().near)));
    row.push_back(stats::text_cell(fmt_g(g.meta().far)));
  }
}

// "View groups: A = views 1, 2 (FOV 30, window 128); ..."
std::string group_note(const RunRecords& run, PrimitiveKind kind) {
  std::string s = "View groups pool the views that differ only by camera orientation: ";
  bool first = true;
  for (int g : run.view_groups(kind)) {
    const ViewGroup* group = any_group(run, kind, g);
    s += (first ? "" : "; ") + group->label + " = views " + join_ints(group->view_numbers()) +
         " (FOV " + fmt_g(group->meta().fov_deg) + ", window " + window_text(group->meta()) + ")";
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
std::vector<double> pooled_all(const RunRecords& run, std::size_t p, PrimitiveKind kind,
                               std::size_t metric) {
  std::vector<const std::vector<double>*> parts;
  for (const ViewGroup* g : run.groups_of(p, kind)) {
    for (const ViewData* v : g->views) parts.push_back(&v->values[metric]);
  }
  return merge_sorted(parts);
}

const char* headline_column(PrimitiveKind kind) {
  switch (kind) {
    case PrimitiveKind::kPoint:
      return "pe";
    case PrimitiveKind::kLine:
      return "lse_u";
    case PrimitiveKind::kTriangle:
      return "te_u";
  }
  return "";
}

}  // namespace

std::string quantile_label(QuantileDefinition q) {
  return q == QuantileDefinition::kHyndmanFan6 ? "Hyndman-Fan 6 (NIST e-Handbook, Dataplot)"
                                               : "Hyndman-Fan 7 (R, NumPy default)";
}

const std::vector<MetricTableSpec>& metric_table_specs() {
  using K = PrimitiveKind;
  static const std::vector<MetricTableSpec> specs = {
      {"3", K::kPoint, "pe", 0, 5, "Summary of non-normalized point rendering errors",
       "table03_pe"},
      {"4", K::kPoint, "pe_norm", 3, 3, "Summary of normalized point rendering errors",
       "table04_pe_norm"},
      {"6", K::kLine, "lse_s_norm", 6, 2,
       "Summary of normalized signed line segment rendering errors", "table06_lse_s_norm"},
      {"7", K::kLine, "lse_u_norm", 3, 3,
       "Summary of normalized unsigned line segment rendering errors", "table07_lse_u_norm"},
      {"9", K::kTriangle, "te_s_norm", 6, 2,
       "Summary of normalized signed triangle rendering errors", "table09_te_s_norm"},
      {"10", K::kTriangle, "te_u_norm", 3, 3,
       "Summary of normalized unsigned triangle rendering errors", "table10_te_u_norm"},
      {"6s", K::kLine, "lse_s", 0, 4, "Summary of non-normalized signed line segment errors",
       "table06s_lse_s"},
      {"7s", K::kLine, "lse_u", 0, 4, "Summary of non-normalized unsigned line segment errors",
       "table07s_lse_u"},
      {"9s", K::kTriangle, "te_s", 0, 3, "Summary of non-normalized signed triangle errors",
       "table09s_te_s"},
      {"10s", K::kTriangle, "te_u", 0, 3, "Summary of non-normalized unsigned triangle errors",
       "table10s_te_u"},
      {"10e", K::kTriangle, "te_u_edge_norm", 0, 4,
       "Summary of unsigned triangle errors per pixel of visible edge", "table10e_te_u_edge_norm"},
  };
  return specs;
}

GroupSummaries::GroupSummaries(const RunRecords& run, QuantileDefinition quantiles, unsigned jobs,
                               stats::BootstrapOptions bootstrap) {
  bootstrap.definition = quantiles;
  struct Task {
    const ViewGroup* group;
    std::size_t metric;
  };
  std::vector<Task> tasks;
  for (const ViewGroup& g : run.groups) {
    for (std::size_t m = 0; m < kind_metrics(g.kind).size(); ++m) tasks.push_back({&g, m});
  }
  std::vector<std::optional<Description>> out(tasks.size());
  std::vector<std::optional<stats::MedianIqrBootstrap>> boot(tasks.size());
  util::run_in_parallel(tasks.size(), jobs, [&](std::size_t i) {
    const std::vector<double> sample = tasks[i].group->pooled(tasks[i].metric);  // ascending
    out[i] = describe_if_any(sample, quantiles);
    if (out[i] && bootstrap.resamples > 0) boot[i] = stats::bootstrap_median_iqr(sample, bootstrap);
  });
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    if (!out[i]) continue;
    const ViewGroup& g = *tasks[i].group;
    const auto key =
        std::make_tuple(g.platform, static_cast<int>(g.kind), tasks[i].metric, g.view_group);
    d_.emplace(key, *out[i]);
    if (boot[i]) b_.emplace(key, *boot[i]);
  }
}

const Description* GroupSummaries::find(std::size_t platform, PrimitiveKind kind,
                                        std::size_t metric, int view_group) const {
  const auto it = d_.find(std::make_tuple(platform, static_cast<int>(kind), metric, view_group));
  return it == d_.end() ? nullptr : &it->second;
}

const stats::MedianIqrBootstrap* GroupSummaries::bootstrap(std::size_t platform, PrimitiveKind kind,
                                                           std::size_t metric,
                                                           int view_group) const {
  const auto it = b_.find(std::make_tuple(platform, static_cast<int>(kind), metric, view_group));
  return it == b_.end() ? nullptr : &it->second;
}

stats::Table uncertainty_table(const RunRecords& run, const GroupSummaries& summaries,
                        const TableOptions& options) {
  stats::Table t;
  t.file_stem = "uncertainty";
  t.title =
      "Uncertainty of Tables 3, 4, 6, 7, 9, 10: bootstrap standard error (SE) and 95% "
      "percentile interval of each median and IQR, in the units and scale of its table";
  for (const char* c : {"Table", "Metric", "View", "Platform"})
    t.columns.push_back({c, stats::Align::kLeft});
  for (const char* c :
       {"n", "Median", "SE", "95% low", "95% high", "IQR", "SE", "95% low", "95% high"})
    t.columns.push_back({c, stats::Align::kRight});
  for (const MetricTableSpec& spec : metric_table_specs()) {
    if (!std::isdigit(static_cast<unsigned char>(spec.number.back()))) continue;  // supplements
    const std::size_t metric = metric_index(spec.kind, spec.column);
    const MetricSpec& m = kind_metrics(spec.kind)[metric];
    const double scale = std::pow(10.0, spec.scale_exponent);
    const int decimals = spec.decimals + 1;  // one more than the table: the SE's first digit
    for (int g : run.view_groups(spec.kind)) {
      for (std::size_t p = 0; p < run.platforms.size(); ++p) {
        const Description* d = summaries.find(p, spec.kind, metric, g);
        const stats::MedianIqrBootstrap* b = summaries.bootstrap(p, spec.kind, metric, g);
        if (!d || !b) continue;
        std::vector<stats::TableCell> row = {
            stats::text_cell(spec.number),
            stats::text_cell(std::string(m.symbol) + " " + scale_text(spec.scale_exponent)),
            stats::text_cell(view_group_label(g)), stats::text_cell(run.platforms[p]),
            stats::text_cell(std::to_string(d->n))};
        for (const auto& [value, e] :
             {std::pair{d->median, b->median}, std::pair{d->iqr, b->iqr}}) {
          row.push_back(stats::number_cell(value * scale, decimals));
          row.push_back(stats::number_cell(e.se * scale, decimals));
          row.push_back(stats::number_cell(e.lo95 * scale, decimals));
          row.push_back(stats::number_cell(e.hi95 * scale, decimals));
        }
        t.rows.push_back(std::move(row));
      }
    }
  }
  t.notes.push_back("Bootstrap: " + std::to_string(options.bootstrap.resamples) +
                    " resamples of each pooled view-group sample, seed " +
                    std::to_string(options.bootstrap.seed) +
                    " (reproducible); each resample's median and quartiles by " +
                    quantile_label(options.quantiles) +
                    "; SE = standard deviation of the resampled statistic; interval = its 2.5% "
                    "and 97.5% percentiles (stats/bootstrap.h).");
  t.notes.push_back(
      "A difference between two cells (two platforms, or ours and the paper's) "
      "larger than 3 x sqrt(SE_a^2 + SE_b^2) is unlikely to be sampling noise.");
  return t;
}

namespace {

// One cell of ours set beside the paper's: a table, statistic, view group and platform.
struct PaperCell {
  const MetricTableSpec* spec = nullptr;
  std::string table, statistic, group, platform;
  double ours = 0, se = 0;  // ours and its bootstrap SE, in the table's scale
  double se_difference = 0;  // SE of ours - paper: ours alone, or with the paper's own (below)
  std::array<double, 2> paper{};  // Platform I, II; NaN: lost in the extraction
  std::array<double, 2> z{};      // (ours - paper) / se_difference; NaN without a paper value
  std::array<bool, 2> beyond{};   // |z| > 3 (or SE 0 and different)
  bool differs() const {  // beyond 3 SE of every platform the paper gives a value for
    bool any = false;
    for (int p = 0; p < 2; ++p) {
      if (std::isnan(paper[p])) continue;
      if (!beyond[p]) return false;
      any = true;
    }
    return any;
  }
};

// Every cell of the paper's tables that the run has: the view group's FOV and window must be the
// paper's. The paper's value has its own sampling error: with `primitives_per_view_group` known,
// its SE is taken as ours x sqrt(N / N_paper) (N: our ok records of the group; the same
// distribution behind both), and se_difference = sqrt(SE^2 + SE_paper^2).
std::vector<PaperCell> paper_cells(const RunRecords& run, const GroupSummaries& summaries,
                                   const TableOptions& options) {
  std::vector<PaperCell> cells;
  for (const PaperTableValues& paper : options.paper) {
    const MetricTableSpec* spec = nullptr;
    for (const MetricTableSpec& s : metric_table_specs())
      if (s.number == paper.number) spec = &s;
    if (!spec || spec->column != paper.column) continue;  // not a table this run makes
    const std::size_t metric = metric_index(spec->kind, spec->column);
    const double scale = std::pow(10.0, paper.scale_exponent);
    for (int stat = 0; stat < 2; ++stat) {
      for (int g : run.view_groups(spec->kind)) {
        if (g < 0 || g > 3) continue;  // groups A-D are 0-3
        const ViewMeta& meta = any_group(run, spec->kind, g)->meta();
        if (meta.fov_deg != paper.fov_deg[g] || meta.width != paper.window[g] ||
            meta.height != paper.window[g])
          continue;  // not the paper's view
        for (std::size_t p = 0; p < run.platforms.size(); ++p) {
          const Description* d = summaries.find(p, spec->kind, metric, g);
          const stats::MedianIqrBootstrap* b = summaries.bootstrap(p, spec->kind, metric, g);
          const ViewGroup* group = run.find_group(p, spec->kind, g);
          if (!d || !b || !group) continue;
          PaperCell c;
          c.spec = spec;
          c.table = paper.number;
          c.statistic = stat == 0 ? "median" : "IQR";
          c.group = view_group_label(g);
          c.platform = run.platforms[p];
          c.ours = (stat == 0 ? d->median : d->iqr) * scale;
          c.se = (stat == 0 ? b->median.se : b->iqr.se) * scale;
          c.se_difference = c.se;
          if (options.paper_primitives_per_group > 0) {
            const VisibilityCounts counts = group->counts();
            std::uint64_t ok = 0;
            for (std::uint64_t n : counts.by_class) ok += n;
            c.se_difference =
                c.se * std::sqrt(1.0 + double(ok) / options.paper_primitives_per_group);
          }
          for (int platform = 0; platform < 2; ++platform) {
            const double value = (stat == 0 ? paper.median : paper.iqr)[platform][g];
            c.paper[platform] = value;
            c.z[platform] = std::nan("");
            if (std::isnan(value)) continue;
            if (c.se_difference <= 0) {
              c.beyond[platform] = c.ours != value;
              continue;
            }
            c.z[platform] = (c.ours - value) / c.se_difference;
            c.beyond[platform] = std::fabs(c.z[platform]) > 3;
          }
          cells.push_back(std::move(c));
        }
      }
    }
  }
  return cells;
}

std::string se_difference_note(const TableOptions& options) {
  if (options.paper_primitives_per_group <= 0)
    return "The SE is ours alone (the paper gives none, nor its sample size here).";
  return "The paper's values have sampling error too: z = (ours - paper) / sqrt(SE^2 + "
         "SE_paper^2), SE_paper = SE x sqrt(N / " +
         stats::format_significant(options.paper_primitives_per_group, 9) +
         ") (N: our records of the view group; the paper's " +
         stats::format_significant(options.paper_primitives_per_group, 9) +
         " primitives per view group; the same distribution assumed).";
}

}  // namespace

stats::Table paper_comparison_table(const RunRecords& run, const GroupSummaries& summaries,
                             const TableOptions& options) {
  stats::Table t;
  t.file_stem = "paper_comparison";
  t.title =
      "Ours beside the paper's: each median and IQR of Tables 3, 4, 6, 7, 9, 10 with its "
      "bootstrap SE, the paper's Platform I and II, and z = (ours - paper) / SE of the difference";
  for (const char* c : {"Table", "Statistic", "View", "Platform"})
    t.columns.push_back({c, stats::Align::kLeft});
  for (const char* c : {"Ours", "SE", "Paper I", "z I", "Paper II", "z II", "Beyond 3 SE of"})
    t.columns.push_back({c, stats::Align::kRight});
  std::size_t flagged = 0, differing = 0;  // beyond 3 SE of one paper platform; of every one
  const std::vector<PaperCell> cells = paper_cells(run, summaries, options);
  for (const PaperCell& c : cells) {
    std::vector<stats::TableCell> row = {stats::text_cell(c.table), stats::text_cell(c.statistic), stats::text_cell(c.group),
                                  stats::text_cell(c.platform), stats::number_cell(c.ours, c.spec->decimals + 1),
                                  stats::number_cell(c.se, c.spec->decimals + 1)};
    std::string beyond_of;  // "I", "II", "I, II"
    for (int platform = 0; platform < 2; ++platform) {
      const double value = c.paper[platform];
      row.push_back(std::isnan(value) ? stats::text_cell("lost") : stats::number_cell(value, c.spec->decimals));
      // z as text: "n/a" without a paper value; "SE 0" when ours has no spread yet differs
      if (std::isnan(value))
        row.push_back(stats::text_cell("n/a"));
      else if (std::isnan(c.z[platform]))
        row.push_back(c.beyond[platform] ? stats::text_cell("SE 0") : stats::number_cell(0, 1));
      else
        row.push_back(stats::number_cell(c.z[platform], 1));
      if (c.beyond[platform])
        beyond_of += (beyond_of.empty() ? "" : ", ") + std::string(platform ? "II" : "I");
    }
    flagged += !beyond_of.empty();
    differing += c.differs();
    row.push_back(stats::text_cell(beyond_of));
    t.rows.push_back(std::move(row));
  }
  t.notes.push_back(
      std::to_string(differing) + " of " + std::to_string(cells.size()) +
      " cells differ from the paper: beyond 3 SE of every paper platform that gives a value (the "
      "count the first page and paper_differences.md use); the other " +
      std::to_string(cells.size() - differing) + " agree with at least one of the paper's "
      "platforms" +
      (flagged > differing ? ", " + std::to_string(flagged - differing) +
                                 " of them beyond 3 SE of the other (column 'Beyond 3 SE of')"
                           : std::string()) +
      ". " + se_difference_note(options) +
      " The platforms differ from the paper's (today's drivers), so z says where, not that "
      "either is wrong. The paper's values are rounded as printed: half a unit of their last "
      "digit can be a good part of an SE of our largest samples (0.0005 against 0.0008 for "
      "Table 4's group D). Where we differ and why: paper_differences.md.");
  for (const PaperTableValues& paper : options.paper)
    t.notes.push_back("Paper Table " + paper.number +
                      (paper.page ? " (page " + std::to_string(paper.page) + ")" : "") + ": " +
                      paper.reading + ".");
  return t;
}

stats::Table paper_differences_table(const RunRecords& run, const GroupSummaries& summaries,
                              const TableOptions& options) {
  stats::Table t;
  t.file_stem = "paper_differences";
  t.title =
      "Where we differ from the paper and why: every cell beyond 3 SE of each of the paper's "
      "platforms that gives a value, with the explanation established for it";
  for (const char* c : {"Table", "Statistic", "View", "Platform"})
    t.columns.push_back({c, stats::Align::kLeft});
  for (const char* c : {"Ours", "Paper I", "z I", "Paper II", "z II"})
    t.columns.push_back({c, stats::Align::kRight});
  t.columns.push_back({"Why", stats::Align::kLeft});
  const std::vector<PaperCell> cells = paper_cells(run, summaries, options);
  std::vector<std::size_t> cited;  // indices into options.paper_differences, in citation order
  std::size_t differing = 0, unexplained = 0;
  for (const PaperCell& c : cells) {
    if (!c.differs()) continue;
    ++differing;
    std::vector<stats::TableCell> row = {stats::text_cell(c.table), stats::text_cell(c.statistic), stats::text_cell(c.group),
                                  stats::text_cell(c.platform),
                                  stats::number_cell(c.ours, c.spec->decimals + 1)};
    for (int platform = 0; platform < 2; ++platform) {
      if (std::isnan(c.paper[platform])) {
        row.push_back(stats::text_cell("lost"));
        row.push_back(stats::text_cell("n/a"));
        continue;
      }
      row.push_back(stats::number_cell(c.paper[platform], c.spec->decimals));
      row.push_back(std::isnan(c.z[platform]) ? stats::text_cell("SE 0")
                                              : stats::number_cell(c.z[platform], 1));
    }
    std::string why = "not explained";
    for (std::size_t d = 0; d < options.paper_differences.size(); ++d) {
      if (!options.paper_differences[d].covers(c.table, c.statistic, c.group, c.platform)) continue;
      auto at = std::find(cited.begin(), cited.end(), d);
      if (at == cited.end()) at = cited.insert(cited.end(), d);
      why = "[" + std::to_string(at - cited.begin() + 1) + "]";
      break;
    }
    unexplained += why == "not explained";
    row.push_back(stats::text_cell(why));
    t.rows.push_back(std::move(row));
  }
  t.notes.push_back(std::to_string(differing) + " of " + std::to_string(cells.size()) +
                    " cells differ from the paper: beyond 3 SE of every paper platform that gives "
                    "a value (the count the first page uses); " + std::to_string(unexplained) +
                    " of them not explained. " + se_difference_note(options));
  for (std::size_t i = 0; i < cited.size(); ++i)
    t.notes.push_back("[" + std::to_string(i + 1) + "] " +
                      options.paper_differences[cited[i]].explanation);
  return t;
}

// So that two platforms' (or the paper's) counts can be compared with their uncertainty.
stats::Table visibility_share_table(const RunRecords& run, PrimitiveKind kind) {
  const int number = kind == PrimitiveKind::kPoint ? 2 : kind == PrimitiveKind::kLine ? 5 : 8;
  stats::Table t;
  t.file_stem = "table0" + std::to_string(number) + "s_" + kind_name(kind) + "_visibility_shares";
  t.title = "Table " + std::to_string(number) + "s (supplements Table " + std::to_string(number) +
            "): the share of " + kind_label_plural(kind) +
            " in each visibility category, percent of the view group's ok records, with "
            "Clopper-Pearson 95% intervals";
  bool multiple = kind == PrimitiveKind::kPoint;
  for (const ViewGroup& g : run.groups)
    if (g.kind == kind) multiple = multiple || g.counts().by_class[4] > 0;
  t.columns = {{"Platform", stats::Align::kLeft},       {"View", stats::Align::kLeft},
               {"Records", stats::Align::kRight},       {"True visible", stats::Align::kRight},
               {"True invisible", stats::Align::kRight}, {"False visible", stats::Align::kRight},
               {"False invisible", stats::Align::kRight}};
  if (multiple) t.columns.push_back({"Multiple visible", stats::Align::kRight});
  const int classes = multiple ? 5 : 4;
  for (std::size_t p = 0; p < run.platforms.size(); ++p) {
    bool first = true;
    for (const ViewGroup* g : run.groups_of(p, kind)) {
      if (first) t.rules_before.push_back(t.rows.size());
      first = false;
      const VisibilityCounts c = g->counts();
      std::uint64_t ok = 0;
      for (std::uint64_t n : c.by_class) ok += n;
      std::vector<stats::TableCell> row = {stats::text_cell(run.platforms[p]), stats::text_cell(g->label),
                                    stats::count_cell(ok)};
      for (int v = 0; v < classes; ++v)
        row.push_back(stats::share_cell(c.by_class[static_cast<std::size_t>(v)], ok));
      t.rows.push_back(std::move(row));
    }
  }
  t.notes = {"Shares of the records with status ok; the interval is exact (Clopper-Pearson, "
             "stats/binomial_interval.h). CSV: the share alone.",
             group_note(run, kind)};
  return t;
}

stats::Table visibility_table(const RunRecords& run, PrimitiveKind kind) {
  const int number = kind == PrimitiveKind::kPoint ? 2 : kind == PrimitiveKind::kLine ? 5 : 8;
  stats::Table t;
  t.file_stem = "table0" + std::to_string(number) + "_" + kind_name(kind) + "_visibility";
  t.title = "Table " + std::to_string(number) + " (mirrors the paper's Table " +
            std::to_string(number) + "): the counts of " + kind_label_plural(kind) +
            " rendered in each visibility category for each view group and platform; counts of "
            "records, unscaled";
  bool multiple = kind == PrimitiveKind::kPoint;
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
  for (std::size_t p = 0; p < run.platforms.size(); ++p) {
    bool first = true;
    for (const ViewGroup* g : run.groups_of(p, kind)) {
      if (first) t.rules_before.push_back(t.rows.size());
      first = false;
      const VisibilityCounts c = g->counts();
      std::vector<stats::TableCell> row = {stats::text_cell(run.platforms[p]), stats::text_cell(g->label)};
      for (int v = 0; v < 4; ++v)
        row.push_back(stats::count_cell(c.by_class[static_cast<std::size_t>(v)]));
      if (multiple) row.push_back(stats::count_cell(c.by_class[4]));
      if (invalid) row.push_back(stats::count_cell(c.invalid));
      if (crash) row.push_back(stats::count_cell(c.crash));
      if (timeout) row.push_back(stats::count_cell(c.timeout));
      t.rows.push_back(std::move(row));
    }
  }
  t.notes = {
      "Classes (paper section 3.4) count records with status ok; invalid, crash and "
      "timeout records are counted apart, in their own columns when there are any.",
      group_note(run, kind)};
  if (kind == PrimitiveKind::kPoint && run.point_margin_px > 0) {
    t.notes.push_back(
        "The paper's point convention (--point-margin-px " +
        stats::format_significant(run.point_margin_px, 6) + "): " +
        std::to_string(run.points_within_margin) +
        " true-invisible points whose projection lies within that many pixels outside the window "
        "are counted false-invisible (docs/method.md, \"Where we differ from the paper\").");
  }
  if (kind != PrimitiveKind::kPoint && multiple) {
    t.notes.push_back(
        "Multiple visible is shown because the records use it for this kind (the "
        "paper uses it for points only).");
  }
  return t;
}

stats::Table metric_table(const RunRecords& run, const GroupSummaries& summaries,
                   const MetricTableSpec& spec, QuantileDefinition quantiles) {
  const std::size_t metric = metric_index(spec.kind, spec.column);
  const MetricSpec& m = kind_metrics(spec.kind)[metric];
  const bool supplement = !std::isdigit(static_cast<unsigned char>(spec.number.back()));
  const std::string paper_number =
      spec.number.substr(0, spec.number.find_first_not_of("0123456789"));
  stats::Table t;
  t.file_stem = spec.file_stem;
  const std::string head = "Table " + spec.number + " (" +
                           (supplement ? "supplement to" : "mirrors") + " the paper's Table " +
                           paper_number + "): " + spec.paper_title + " " + m.symbol + ", " +
                           unit_name(m.unit) + ", values ";
  const std::string tail =
      "; median and IQR by view group and platform; quartiles " + quantile_label(quantiles);
  t.title = head + scale_text(spec.scale_exponent) + tail;  // LaTeX typesets x10^k (table_writer)

  const bool planes = planes_vary(run);
  add_view_columns(t, planes);
  for (const std::string& p : run.platforms) {
    t.groups.push_back({p, 2});
    t.columns.push_back({"Median", stats::Align::kRight});
    t.columns.push_back({"IQR", stats::Align::kRight});
  }
  t.groups.insert(t.groups.begin(), stats::ColumnGroup{"", planes ? 5u : 3u});

  const double scale = std::pow(10.0, spec.scale_exponent);
  bool no_data = false;
  for (int g : run.view_groups(spec.kind)) {
    std::vector<stats::TableCell> row;
    add_view_cells(row, *any_group(run, spec.kind, g), planes);
    for (std::size_t p = 0; p < run.platforms.size(); ++p) {
      if (const Description* d = summaries.find(p, spec.kind, metric, g)) {
        row.push_back(stats::number_cell(d->median * scale, spec.decimals));
        row.push_back(stats::number_cell(d->iqr * scale, spec.decimals));
      } else {
        row.push_back(stats::text_cell("no data"));
        row.push_back(stats::text_cell("no data"));
        no_data = true;
      }
    }
    t.rows.push_back(std::move(row));
  }

  t.notes.push_back(std::string("Units: ") + unit_long(m.unit) +
                    (spec.scale_exponent
                         ? "; shown x10^" + std::to_string(spec.scale_exponent) +
                               " (1.000 means 1e-" + std::to_string(spec.scale_exponent) + ")"
                         : "") +
                    ".");
  t.notes.push_back(std::string("Sample: true-visible ") + kind_label_plural(spec.kind) +
                    " with status ok and a value of " + spec.column + ".");
  t.notes.push_back(group_note(run, spec.kind));
  std::uint64_t missing = 0;
  for (const auto& [key, data] : run.views) {
    if (key.kind == spec.kind) missing += data.missing[metric];
  }
  if (missing > 0) {
    t.notes.push_back(std::to_string(missing) + " true-visible records have no value of " +
                      spec.column + " (not measured by the runner that wrote them).");
  }
  if (no_data) {
    t.notes.push_back(
        "no data: no true-visible record of this view group and platform has a "
        "value.");
  }
  if (spec.number == "6") {
    t.notes.push_back(
        "Scale x10^6: the exponent is lost in the paper's extracted text; x10^6 makes its "
        "Platform II medians 0.041-0.046 px in all four views (344.89e-6 x 128 px, 45.39e-6 x 907 "
        "px), below the median LSEu of 0.25 px as abs(mean signed offset) <= mean abs(offset) "
        "requires; "
        "x10^5 would give 0.44 px, above LSEu.");
  }
  if (spec.number == "9") {
    t.notes.push_back(
        "Scale x10^6, as the paper's values imply (IQRs of 1-4.5 px^2 at 128 px, "
        "below the median TEu of 26 px^2).");
  }
  return t;
}

stats::Table physical_units_table(const RunRecords& run, const GroupSummaries& summaries,
                           const TableOptions& options) {
  struct Column {
    PrimitiveKind kind;
    const char* metric;
    const char* name;
    int power;  // 1: length, 2: area
    int decimals;
  };
  std::vector<Column> columns;
  const std::vector<PrimitiveKind> kinds = run.kinds();
  const auto has = [&](PrimitiveKind k) {
    return std::find(kinds.begin(), kinds.end(), k) != kinds.end();
  };
  if (has(PrimitiveKind::kPoint)) columns.push_back({PrimitiveKind::kPoint, "pe", "PE (mm)", 1, 3});
  if (has(PrimitiveKind::kLine)) {
    columns.push_back({PrimitiveKind::kLine, "lse_u", "LSEu (mm)", 1, 3});
  }
  if (has(PrimitiveKind::kTriangle)) {
    columns.push_back({PrimitiveKind::kTriangle, "te_u", "TEu (mm^2)", 2, 2});
  }

  stats::Table t;
  t.file_stem = "table11_physical_units";
  t.title =
      "Table 11 (mirrors the paper's Table 11): median rendering errors converted to "
      "physical units for pixel pitches of ";
  for (std::size_t i = 0; i < options.pixel_pitches_mm.size(); ++i) {
    t.title += (i ? ", " : "") + fmt_g(options.pixel_pitches_mm[i]);
  }
  t.title += " mm: PE and LSEu in mm, TEu in mm^2, unscaled; medians, quartiles " +
             quantile_label(options.quantiles);
  t.columns = {{"Pitch (mm)", stats::Align::kRight},
               {"View", stats::Align::kLeft},
               {"FOV", stats::Align::kRight},
               {"Win Size", stats::Align::kRight}};
  t.groups.push_back({"", 4});
  for (const std::string& p : run.platforms) {
    t.groups.push_back({p, columns.size()});
    for (const Column& c : columns) t.columns.push_back({c.name, stats::Align::kRight});
  }

  // all view groups pooled, per platform and column (the paper's overall 0.396 px)
  std::vector<std::vector<std::optional<Description>>> all(
      run.platforms.size(), std::vector<std::optional<Description>>(columns.size()));
  util::run_in_parallel(run.platforms.size() * columns.size(), options.jobs, [&](std::size_t i) {
    const std::size_t p = i / columns.size();
    const Column& c = columns[i % columns.size()];
    all[p][i % columns.size()] = describe_if_any(
        pooled_all(run, p, c.kind, metric_index(c.kind, c.metric)), options.quantiles);
  });

  // view groups of any kind, by number
  std::vector<int> groups;
  for (const ViewGroup& g : run.groups) groups.push_back(g.view_group);
  std::sort(groups.begin(), groups.end());
  groups.erase(std::unique(groups.begin(), groups.end()), groups.end());

  bool no_data = false;
  for (double pitch : options.pixel_pitches_mm) {
    t.rules_before.push_back(t.rows.size());
    for (std::size_t gi = 0; gi <= groups.size(); ++gi) {
      const bool pooled = gi == groups.size();
      std::vector<stats::TableCell> row = {stats::text_cell(fmt_g(pitch))};
      if (pooled) {
        row.push_back(stats::text_cell("all"));
        row.push_back(stats::text_cell(""));
        row.push_back(stats::text_cell(""));
      } else {
        const ViewGroup* any = nullptr;
        for (PrimitiveKind k : kinds) {
          if (!any) any = any_group(run, k, groups[gi]);
        }
        row.push_back(stats::text_cell(any->label));
        row.push_back(stats::text_cell(fmt_g(any->meta().fov_deg)));
        row.push_back(stats::text_cell(window_text(any->meta())));
      }
      for (std::size_t p = 0; p < run.platforms.size(); ++p) {
        for (std::size_t c = 0; c < columns.size(); ++c) {
          const Column& col = columns[c];
          const Description* d =
              pooled ? (all[p][c] ? &*all[p][c] : nullptr)
                     : summaries.find(p, col.kind, metric_index(col.kind, col.metric), groups[gi]);
          if (d) {
            row.push_back(stats::number_cell(d->median * std::pow(pitch, col.power), col.decimals));
          } else {
            row.push_back(stats::text_cell("no data"));
            no_data = true;
          }
        }
      }
      t.rows.push_back(std::move(row));
    }
  }
  t.notes = {
      "mm = median in px x pitch; mm^2 = median in px^2 x pitch^2 (paper section 4: 0.396 px "
      "x 0.255 mm = 0.101 mm). The medians in pixels are in Tables 3, 7s and 10s.",
      "all: every view group of the platform pooled (different windows mixed, as the "
      "paper's overall PE of 0.396 px)."};
  if (no_data) t.notes.push_back("no data: no true-visible record with a value.");
  return t;
}

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
    PrimitiveKind kind;
    const ViewGroup* group;  // nullptr: all groups pooled
  };
  std::vector<Row> rows;
  for (std::size_t p = 0; p < run.platforms.size(); ++p) {
    for (PrimitiveKind k : run.kinds()) {
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
    const std::size_t metric = metric_index(r.kind, headline_column(r.kind));
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
      row.push_back(stats::text_cell(fmt_g(r.group->meta().fov_deg)));
      row.push_back(stats::text_cell(window_text(r.group->meta())));
    } else {
      row.push_back(stats::text_cell("all"));
      row.push_back(stats::text_cell(""));
      row.push_back(stats::text_cell(""));
    }
    pair(row, computed[i].all, true, 2);
    pair(row, computed[i].visible, true, 2);
    const std::size_t metric = metric_index(r.kind, headline_column(r.kind));
    const MetricSpec& spec = kind_metrics(r.kind)[metric];
    row.push_back(stats::text_cell(std::string(spec.symbol) + " (" + unit_name(spec.unit) + ")"));
    // the decimals of the paper's non-normalized tables: PE 5 (Table 3), LSEu 4, TEu 3
    pair(row, computed[i].error, false,
         r.kind == PrimitiveKind::kPoint  ? 5
         : r.kind == PrimitiveKind::kLine ? 4
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
      "errors."};
  if (std::any_of(run.platforms.begin(), run.platforms.end(), is_vulkan_platform))
    t.notes.push_back(kVulkanRenderTimeNote);
  return t;
}

std::vector<PlatformComparison> compare_platforms(const RunRecords& run,
                                                  const GroupSummaries& summaries,
                                                  const TableOptions& options) {
  std::vector<PlatformComparison> out;
  for (PrimitiveKind kind : run.kinds()) {
    for (std::size_t m = 0; m < kind_metrics(kind).size(); ++m) {
      for (int g : run.view_groups(kind)) {
        for (std::size_t a = 0; a < run.platforms.size(); ++a) {
          for (std::size_t b = a + 1; b < run.platforms.size(); ++b) {
            if (!run.find_group(a, kind, g) || !run.find_group(b, kind, g)) continue;
            PlatformComparison c;
            c.kind = kind;
            c.metric = m;
            c.view_group = g;
            c.label = view_group_label(g);
            c.platform_a = a;
            c.platform_b = b;
            out.push_back(std::move(c));
          }
        }
      }
    }
  }
  util::run_in_parallel(out.size(), options.jobs, [&](std::size_t i) {
    PlatformComparison& c = out[i];
    std::vector<std::vector<double>> samples = {
        run.find_group(c.platform_a, c.kind, c.view_group)->pooled(c.metric),
        run.find_group(c.platform_b, c.kind, c.view_group)->pooled(c.metric)};
    const auto summary = [&](std::size_t p) -> std::optional<Description> {
      const Description* d = summaries.find(p, c.kind, c.metric, c.view_group);
      return d ? std::optional<Description>(*d) : std::nullopt;
    };
    c.a = summary(c.platform_a);
    c.b = summary(c.platform_b);
    if (c.a && c.b) c.comparison = compare_samples(samples, options.comparison);
  });
  return out;
}

stats::Table cross_platform_table(const RunRecords& run, const std::vector<PlatformComparison>& rows,
                           const TableOptions& options) {
  stats::Table t;
  t.file_stem = "cross_platform";
  t.title =
      "Cross-platform comparison per view group and metric (paper section 4, Figs. 5, 7, 9, "
      "13): medians and IQRs, differences a - b in metric units, p-values on raw and "
      "Box-Cox data, alpha = " +
      stats::format_significant(options.alpha, 3) + "; quartiles " + quantile_label(options.quantiles);
  for (const char* c : {"Kind", "Metric", "Units", "View", "Platform a", "Platform b"}) {
    t.columns.push_back({c, stats::Align::kLeft});
  }
  for (const char* c : {"n a", "n b", "Median a", "Median b", "Median a-b", "IQR a", "IQR b",
                        "IQR a-b", "t pooled p", "Welch p", "F p", "Levene med p", "BC lambda",
                        "BC t pooled p", "BC Welch p", "BC F p", "BC Levene med p"}) {
    t.columns.push_back({c, stats::Align::kRight});
  }
  t.columns.push_back({"Location", stats::Align::kLeft});
  t.columns.push_back({"Spread", stats::Align::kLeft});
  const auto flag = [&](const TestOutcome& o) {
    if (!o.defined) return stats::text_cell("undefined");
    return stats::text_cell(o.p_value < options.alpha ? "differs" : "same");
  };
  for (const PlatformComparison& c : rows) {
    const MetricSpec& spec = kind_metrics(c.kind)[c.metric];
    std::vector<stats::TableCell> row = {
        stats::text_cell(kind_name(c.kind)),           stats::text_cell(spec.symbol),
        stats::text_cell(unit_name(spec.unit)),        stats::text_cell(c.label),
        stats::text_cell(run.platforms[c.platform_a]), stats::text_cell(run.platforms[c.platform_b]),
        stats::count_cell(c.a ? c.a->n : 0),           stats::count_cell(c.b ? c.b->n : 0)};
    const stats::TableCell none = stats::text_cell("no data");
    if (c.a && c.b) {
      row.push_back(stats::significant_cell(c.a->median, 5));
      row.push_back(stats::significant_cell(c.b->median, 5));
      row.push_back(stats::significant_cell(c.a->median - c.b->median, 4));
      row.push_back(stats::significant_cell(c.a->iqr, 5));
      row.push_back(stats::significant_cell(c.b->iqr, 5));
      row.push_back(stats::significant_cell(c.a->iqr - c.b->iqr, 4));
      const SampleComparison& s = c.comparison;
      for (const TestOutcome* o :
           {&s.raw.location, &s.raw.welch, &s.raw.f_test, &s.raw.levene_median}) {
        row.push_back(p_value_cell(*o));
      }
      row.push_back(s.box_cox.applicable ? stats::significant_cell(s.box_cox.lambda, 3)
                                         : stats::text_cell("n/a"));
      for (const TestOutcome* o : {&s.transformed.location, &s.transformed.welch,
                                   &s.transformed.f_test, &s.transformed.levene_median}) {
        row.push_back(p_value_cell(*o));
      }
      row.push_back(flag(s.raw.welch));
      row.push_back(flag(s.raw.levene_median));
    } else {
      for (std::size_t i = row.size(); i < t.columns.size(); ++i) row.push_back(none);
    }
    t.rows.push_back(std::move(row));
  }
  t.notes = {
      "Location: Welch t test on raw data (variances not assumed equal); Spread: Levene "
      "test with median centre on raw data; 'differs' when p < alpha.",
      "BC: Box-Cox transformed, lambda by maximum PPCC on both platforms' pooled data "
      "(systematic subsample of at most " +
          std::to_string(options.comparison.box_cox_subsample) +
          " order statistics), shift 1 - min when min <= 0; n/a: not applicable.",
      "With samples of 10^5 even tiny differences are significant: read the differences "
      "of medians and IQRs, in metric units, for their size."};
  return t;
}

std::vector<stats::Table> paper_tables(const RunRecords& run, const TableOptions& options) {
  const GroupSummaries summaries(run, options.quantiles, options.jobs, options.bootstrap);
  const std::vector<PrimitiveKind> kinds = run.kinds();
  const auto has = [&](PrimitiveKind k) {
    return std::find(kinds.begin(), kinds.end(), k) != kinds.end();
  };
  std::vector<stats::Table> tables;
  const auto metric_tables = [&](PrimitiveKind kind, bool supplements) {
    for (const MetricTableSpec& spec : metric_table_specs()) {
      const bool is_supplement = !std::isdigit(static_cast<unsigned char>(spec.number.back()));
      if (spec.kind == kind && is_supplement == supplements) {
        tables.push_back(metric_table(run, summaries, spec, options.quantiles));
        if (!is_supplement && options.bootstrap.resamples > 0)
          tables.back().notes.push_back(
              "The bootstrap standard error and 95% interval of every "
              "cell: uncertainty.md.");
      }
    }
  };
  for (PrimitiveKind kind : kAllKinds) {
    if (!has(kind)) continue;
    tables.push_back(visibility_table(run, kind));
    tables.push_back(visibility_share_table(run, kind));
    metric_tables(kind, false);
  }
  for (PrimitiveKind kind : kAllKinds) {
    if (has(kind)) metric_tables(kind, true);
  }
  if (!kinds.empty() && options.bootstrap.resamples > 0)
    tables.push_back(uncertainty_table(run, summaries, options));
  if (!kinds.empty() && options.bootstrap.resamples > 0 && !options.paper.empty()) {
    stats::Table comparison = paper_comparison_table(run, summaries, options);
    if (!comparison.rows.empty()) {
      tables.push_back(std::move(comparison));
      tables.push_back(paper_differences_table(run, summaries, options));
    }
  }
  if (!kinds.empty()) tables.push_back(physical_units_table(run, summaries, options));
  if (!kinds.empty()) tables.push_back(speed_table(run, options));
  if (run.platforms.size() > 1) {
    tables.push_back(
        cross_platform_table(run, compare_platforms(run, summaries, options), options));
  }
  return tables;
}

}  // namespace ra::analysis
