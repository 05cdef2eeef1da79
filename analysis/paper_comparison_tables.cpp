// Our cells beside the paper's published values (paper_tables.h): the comparison table and the
// table of the differences beyond their sampling error.
#include "analysis/paper_tables.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "analysis/paper_table_parts.h"

namespace ra::analysis {

using namespace table_parts;
using stats::Description;
using stats::QuantileDefinition;

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
  stats::add_columns(t, {"Table", "Statistic", "View", "Platform"}, stats::Align::kLeft);
  stats::add_columns(t, {"Ours", "SE", "Paper I", "z I", "Paper II", "z II", "Beyond 3 SE of"},
                     stats::Align::kRight);
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
  stats::add_columns(t, {"Table", "Statistic", "View", "Platform"}, stats::Align::kLeft);
  stats::add_columns(t, {"Ours", "Paper I", "z I", "Paper II", "z II"}, stats::Align::kRight);
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

}  // namespace ra::analysis
