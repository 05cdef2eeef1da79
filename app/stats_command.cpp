// `renderaudit stats describe|compare|anova|regress`: the statistics of the analysis stage on any
// CSV column, so that a reader can check a report's numbers, or compare two runs, by hand, and fit
// rendering-time models by least squares.
// Methods and conventions: stats/descriptive.h, hypothesis_tests.h, box_cox.h (NIST e-Handbook),
// linear_regression.h (QR least squares, NIST StRD).
//
// Output (its presentation: stats_presentation.h): human-readable text, or with --json one JSON
// object (snake_case keys, doubles written so that they read back exactly). A statistic that is
// undefined for the data (both samples constant, say) is written as null with a "reason"; NaN
// never appears.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "analysis/run_completeness.h"
#include "rundir/records_format.h"
#include "rundir/run_folder.h"
#include "app/commands.h"
#include "app/stats_presentation.h"
#include "rundir/experiment.h"
#include "rundir/manifest.h"
#include "rundir/records_format.h"
#include "rundir/run_experiment.h"
#include "rundir/shard.h"
#include "rundir/shard_records.h"
#include "stats/box_cox.h"
#include "stats/column_samples.h"
#include "stats/descriptive.h"
#include "stats/hypothesis_tests.h"
#include "stats/linear_regression.h"
#include "util/errors.h"

namespace ra::app {
namespace {

using namespace stats_presentation;
using stats::QuantileDefinition;
using Sample = stats::ColumnSample;

struct StatsOptions {
  std::vector<std::string> files;
  std::string column;
  std::string group;
  std::string value;
  std::string quantiles = "hf6";
  std::string y;               // regress: response column
  std::vector<std::string> x;  // regress: predictor columns
  std::string poly;            // regress: "COLUMN:DEGREE", a polynomial in one column
  bool no_intercept = false;   // regress
  bool json = false;
  std::vector<std::string> where;  // describe: COLUMN=VALUE conditions every row must meet
  bool allow_incomplete = false;   // describe: a run directory with missing shards
};

QuantileDefinition quantile_definition(const std::string& name) {
  return name == "hf7" ? QuantileDefinition::kHyndmanFan7 : QuantileDefinition::kHyndmanFan6;
}

// The records files of a run directory, and the planned shards it lacks.
struct RunRecordsFiles {
  std::vector<std::string> files;
  std::vector<std::string> missing;  // shard ids, in plan order
  uint64_t shards_planned = 0, primitives_planned = 0, primitives_missing = 0;
};

// The records files of a run directory, each judged by the seal rule (rundir/shard_records.h):
// a damaged file, or a file that is not one of the plan's shards, stops with its name. A
// directory without experiment.toml (records gathered by hand) lists records/ as it is.
RunRecordsFiles run_records_files(const std::string& dir) {
  namespace fs = std::filesystem;
  RunRecordsFiles out;
  std::vector<std::string>& files = out.files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(rundir::run_folder::records(dir), ec))
    if (ra::rundir::is_records_file_name(e.path().filename().string()))
      files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  if (!fs::exists(rundir::run_folder::experiment(dir))) return out;
  const rundir::Experiment exp = rundir::load_run_experiment(dir);
  std::set<std::string> trusted;
  for (const rundir::Shard& s : rundir::plan_shards(exp))
    if (const std::string p = rundir::trusted_records_path(dir, s); !p.empty()) trusted.insert(p);
  for (const std::string& f : files)
    if (!trusted.count(f))
      throw util::UserError(f + ": not a shard of the run's plan (" +
                            rundir::run_folder::experiment(dir) +
                            "): its rows would be counted with the run's; move it out of records/");
  for (const rundir::Shard& s : rundir::planned_shards_of_run(dir, exp)) {
    ++out.shards_planned;
    out.primitives_planned += s.size();
    if (rundir::find_shard_records(dir, s, false).path.empty())
      out.missing.push_back(s.id()), out.primitives_missing += s.size();
  }
  return out;
}

// "2 of 32 planned shards have no records file (X, Y, ...); N of M planned primitives are there"
std::string missing_shards_text(const RunRecordsFiles& r) {
  std::string ids;
  for (std::size_t i = 0; i < r.missing.size() && i < 3; ++i) ids += (i ? ", " : "") + r.missing[i];
  if (r.missing.size() > 3) ids += ", ...";
  return std::to_string(r.missing.size()) + " of " + std::to_string(r.shards_planned) +
         " planned shards have no records file (" + ids + "); " +
         std::to_string(r.primitives_planned - r.primitives_missing) + " of " +
         std::to_string(r.primitives_planned) + " planned primitives are there";
}

// The rows of `column` where every `where` condition (COLUMN=VALUE, the cell's text) holds, from
// a CSV file or from a run directory's records (DIR/records/*.csv, all with the records header).
Sample read_selected_sample(const std::string& path, const std::string& column,
                            const std::vector<std::string>& where, bool allow_incomplete,
                            std::string* incomplete) {
  namespace fs = std::filesystem;
  const stats::RowConditions conditions = stats::parse_row_conditions(where);
  std::vector<std::string> files;
  std::string name = path;
  if (fs::is_directory(path)) {
    const RunRecordsFiles run = run_records_files(path);
    files = run.files;
    if (!run.missing.empty()) {
      *incomplete = missing_shards_text(run);
      if (!allow_incomplete)
        throw analysis::IncompleteRunError(
            path + ": incomplete: " + *incomplete + ", so no statistic of it is the run's. Finish "
            "the run (the same `renderaudit run` command; `renderaudit status " + path +
            "` says why), or pass --allow-incomplete to describe the records it holds");
    }
    if (files.empty())
      throw util::UserError(
          path +
          ": a directory without records/*.csv or *.csv.zst (give a CSV file or a "
          "run directory)");
    name = path + "/records (" + std::to_string(files.size()) + " files)";
  } else {
    files.push_back(path);
  }
  Sample s{name, column, {}, 0};
  for (const std::string& file : files) stats::add_selected_values(file, conditions, s);
  stats::require_two_selected_values(s);
  return s;
}

void run_describe(const StatsOptions& o) {
  std::string incomplete;  // what a run directory lacks, when --allow-incomplete went on
  const Sample s =
      read_selected_sample(o.files.at(0), o.column, o.where, o.allow_incomplete, &incomplete);
  if (!incomplete.empty())
    std::fprintf(stderr, "renderaudit stats: %s: incomplete run: %s\n", o.files.at(0).c_str(),
                 incomplete.c_str());
  const stats::Description d = stats::describe(s.values, quantile_definition(o.quantiles));
  if (o.json) {
    json j = header_json("stats describe");
    j["quantile_definition"] = stats::quantile_definition_name(quantile_definition(o.quantiles));
    j["file"] = s.file;
    j["column"] = s.column;
    if (!o.where.empty()) j["where"] = o.where;
    j["n_missing"] = s.n_missing;
    if (!incomplete.empty()) j["incomplete_run"] = incomplete;
    j["description"] = description_json(d);
    print_json(j);
    return;
  }
  std::string selected;
  for (const std::string& w : o.where) selected += (selected.empty() ? ", rows where " : " and ") + w;
  out("%s, column '%s'%s (%zu empty cells skipped); quartiles: %s\n", s.file.c_str(),
      s.column.c_str(), selected.c_str(), s.n_missing,
      stats::quantile_definition_name(quantile_definition(o.quantiles)));
  if (!incomplete.empty()) out("incomplete run: %s\n", incomplete.c_str());
  print_description_rows({d}, {s.column});
}

void run_compare(const StatsOptions& o) {
  const Sample a = stats::read_column_sample(o.files.at(0), o.column);
  const Sample b = stats::read_column_sample(o.files.at(1), o.column);
  const QuantileDefinition q = quantile_definition(o.quantiles);
  const stats::Description da = stats::describe(a.values, q);
  const stats::Description db = stats::describe(b.values, q);
  const Reported pooled = t_report(a.values, b.values, true);
  const Reported welch = t_report(a.values, b.values, false);
  const Reported f = report_test(
      {"statistic", "df1", "df2", "p_value"},
      [&] { return stats::f_test_variances(a.values, b.values); },
      [](const stats::FTestResult& f, Reported& r) { fill_f(f, r, "F"); });
  std::string levene_text;
  const json levene = levene_reports({a.values, b.values}, levene_text);
  const stats::BoxCoxResult ppcc_a = stats::box_cox_lambda(a.values, stats::BoxCoxMethod::kPpcc);
  const stats::BoxCoxResult ppcc_b = stats::box_cox_lambda(b.values, stats::BoxCoxMethod::kPpcc);
  const stats::BoxCoxResult mle_a = stats::box_cox_lambda(a.values, stats::BoxCoxMethod::kMle);
  const stats::BoxCoxResult mle_b = stats::box_cox_lambda(b.values, stats::BoxCoxMethod::kMle);

  if (o.json) {
    json j = header_json("stats compare");
    j["quantile_definition"] = stats::quantile_definition_name(quantile_definition(o.quantiles));
    j["column"] = o.column;
    j["a"] = {{"file", a.file}, {"n_missing", a.n_missing}, {"description", description_json(da)}};
    j["b"] = {{"file", b.file}, {"n_missing", b.n_missing}, {"description", description_json(db)}};
    j["t_test_pooled"] = pooled.j;
    j["t_test_welch"] = welch.j;
    j["f_test"] = f.j;
    j["levene"] = levene;
    j["box_cox"] = {{"a", {{"ppcc", box_cox_json(ppcc_a)}, {"mle", box_cox_json(mle_a)}}},
                    {"b", {{"ppcc", box_cox_json(ppcc_b)}, {"mle", box_cox_json(mle_b)}}}};
    print_json(j);
    return;
  }
  out("A: %s\nB: %s\ncolumn '%s'; quartiles: %s\n\n", a.file.c_str(), b.file.c_str(),
      o.column.c_str(), stats::quantile_definition_name(q));
  print_description_rows({da, db}, {"A", "B"});
  out("\nTests of A against B (two-sided p-values; e-Handbook 1.3.5.3, 1.3.5.9, 1.3.5.10)\n");
  out("  t test, pooled variance     : %s\n", pooled.text.c_str());
  out("  t test, Welch               : %s\n", welch.text.c_str());
  out("  F test, var A / var B       : %s\n", f.text.c_str());
  out("%s", levene_text.c_str());
  out("\nBox-Cox lambda (e-Handbook 1.3.3.6), search range [-2, 2]\n");
  out("  A, max PPCC                 : %s\n", box_cox_text(ppcc_a).c_str());
  out("  A, max likelihood           : %s\n", box_cox_text(mle_a).c_str());
  out("  B, max PPCC                 : %s\n", box_cox_text(ppcc_b).c_str());
  out("  B, max likelihood           : %s\n", box_cox_text(mle_b).c_str());
}

void run_anova(const StatsOptions& o) {
  const std::string& file = o.files.at(0);
  const stats::GroupedValues grouped = stats::read_grouped_values(file, o.group, o.value);
  const std::vector<std::string>& names = grouped.names;
  const std::vector<std::vector<double>>& groups = grouped.groups;
  const std::size_t n = grouped.n, n_missing = grouped.n_missing;

  const Reported anova = report_test(
      {"f", "p_value"}, [&] { return stats::one_way_anova(groups); },
      [](const stats::AnovaResult& a, Reported& r) {
        r.j = json{{"k", a.k},
                   {"n", a.n},
                   {"df_between", number(a.df_between)},
                   {"df_within", number(a.df_within)},
                   {"ss_between", number(a.ss_between)},
                   {"ss_within", number(a.ss_within)},
                   {"ms_between", number(a.ms_between)},
                   {"ms_within", number(a.ms_within)},
                   {"f", number(a.f)},
                   {"p_value", number(a.p_value)},
                   {"r_squared", number(a.r_squared)},
                   {"residual_sd", number(a.residual_sd)}};
        char buf[1024];
        std::snprintf(buf, sizeof buf,
                      "  %-8s %8s %24s %24s %16s %16s\n"
                      "  %-8s %8s %24s %24s %16s %16s\n"
                      "  %-8s %8s %24s %24s\n"
                      "  R-squared = %s, residual SD = %s\n",
                      "source", "df", "SS", "MS", "F", "p", "between",
                      text_number(a.df_between).c_str(), text_number(a.ss_between).c_str(),
                      text_number(a.ms_between).c_str(), text_number(a.f).c_str(),
                      text_number(a.p_value).c_str(), "within", text_number(a.df_within).c_str(),
                      text_number(a.ss_within).c_str(), text_number(a.ms_within).c_str(),
                      text_number(a.r_squared).c_str(), text_number(a.residual_sd).c_str());
        r.text = buf;
      });
  std::string levene_text;
  const json levene = levene_reports(groups, levene_text);

  if (o.json) {
    json j = header_json("stats anova");
    j["file"] = file;
    j["group_column"] = o.group;
    j["value_column"] = o.value;
    j["n_missing"] = n_missing;
    json gj = json::array();
    for (std::size_t g = 0; g < groups.size(); ++g) {
      const stats::MeanVariance mv = stats::mean_and_variance(groups[g]);
      gj.push_back({{"name", names[g]},
                    {"n", groups[g].size()},
                    {"mean", number(mv.mean)},
                    {"sd", number(std::sqrt(mv.variance))}});
    }
    j["groups"] = gj;
    j["anova"] = anova.j;
    j["levene"] = levene;
    print_json(j);
    return;
  }
  out("%s: '%s' by '%s', %zu groups, %zu values (%zu rows skipped: empty cells)\n\n", file.c_str(),
      o.value.c_str(), o.group.c_str(), groups.size(), n, n_missing);
  out("  %-16s %8s %24s %24s\n", "group", "n", "mean", "sd");
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const stats::MeanVariance mv = stats::mean_and_variance(groups[g]);
    out("  %-16s %8zu %24s %24s\n", names[g].c_str(), groups[g].size(),
        text_number(mv.mean).c_str(), text_number(mv.sd).c_str());
  }
  out("\nOne-way ANOVA (e-Handbook 1.3.5.4)\n");
  if (anova.text.rfind("undefined", 0) == 0) {
    out("  %s\n", anova.text.c_str());
  } else {
    out("%s", anova.text.c_str());
  }
  out("\nLevene tests of equal variances (e-Handbook 1.3.5.10)\n%s", levene_text.c_str());
}

// Least squares of one column on others, or on a polynomial in one column. Rows with an empty
// cell in any of the columns used are skipped and counted; a cell that is not a number stops with
// file:line (CsvTable::number).
void run_regress(const StatsOptions& o) {
  const std::string& file = o.files.at(0);
  if (o.x.empty() && o.poly.empty()) {
    throw util::UserError(file +
                          ": name the predictors with --x COLUMN[,COLUMN...] or a polynomial "
                          "with --poly COLUMN:DEGREE");
  }
  int degree = 0;
  std::vector<std::string> columns = o.x;
  if (!o.poly.empty()) {
    auto [column, d] = stats::parse_polynomial_spec(file, o.poly);
    columns = {column};
    degree = d;
  }
  stats::check_predictor_names(file, columns, o.y);
  const stats::RegressionData data = stats::read_regression_data(file, o.y, columns);
  const std::vector<double>& y = data.y;
  const std::vector<std::vector<double>>& predictors = data.x;
  const std::size_t n_missing = data.n_missing;

  stats::LinearFit fit;
  const std::string design =
      degree > 0 ? "a polynomial of degree " + std::to_string(degree) + " in '" + columns[0] + "'"
                 : std::to_string(columns.size()) + " predictor(s)";
  try {
    fit = degree > 0
              ? stats::fit_polynomial(predictors[0], y, degree, !o.no_intercept, columns[0])
              : stats::fit_least_squares(predictors, y, !o.no_intercept, columns);
  } catch (const util::UserError& e) {
    throw util::UserError(file + ": '" + o.y + "' on " +
                          (o.no_intercept ? "" : "an intercept and ") + design + ", " +
                          std::to_string(y.size()) + " complete row(s) (" +
                          std::to_string(n_missing) + " skipped for empty cells): " + e.what());
  }
  std::vector<Reported> tests;
  for (std::size_t j = 0; j < fit.coefficients.size(); ++j) {
    tests.push_back(report_test(
        {"t_value", "p_value"}, [&] { return stats::coefficient_t_test(fit, j); },
        [](const stats::CoefficientTest& t, Reported& r) {
          r.j = json{{"t_value", number(t.t)}, {"p_value", number(t.p_value)}};
          char buf[128];
          std::snprintf(buf, sizeof buf, " %16s %16s", text_number(t.t).c_str(),
                        text_number(t.p_value).c_str());
          r.text = buf;
        }));
  }
  const char* r2_definition = fit.r_squared_centred ? "centred" : "uncentred";
  const std::string r2_reason = fit.r_squared_centred
                                    ? "y is constant: no variation about its mean to explain"
                                    : "y is 0 in every row: no variation about 0 to explain";

  if (o.json) {
    json j = header_json("stats regress");
    j["file"] = file;
    j["y_column"] = o.y;
    j["x_columns"] = columns;
    if (degree > 0) j["polynomial_degree"] = degree;
    j["intercept"] = fit.intercept;
    j["method"] = stats::fit_method_name(fit.method);
    j["condition_number"] = number(fit.condition_number);
    j["n"] = fit.n;
    j["n_missing"] = n_missing;
    j["df"] = fit.df;
    j["rank"] = fit.rank;
    json cj = json::array();
    for (std::size_t k = 0; k < fit.coefficients.size(); ++k) {
      json c{{"name", fit.names[k]},
             {"estimate", number(fit.coefficients[k])},
             {"sd", number(fit.standard_deviations[k])}};
      c.update(tests[k].j);
      cj.push_back(c);
    }
    j["coefficients"] = cj;
    j["residual_sd"] = number(fit.residual_sd);
    j["rss"] = number(fit.rss);
    j["r_squared_definition"] = r2_definition;
    if (fit.r_squared) {
      j["r_squared"] = number(*fit.r_squared);
    } else {
      j["r_squared"] = nullptr;
      j["r_squared_reason"] = r2_reason;
    }
    print_json(j);
    return;
  }
  std::string predictors_text;
  for (const auto& name : columns)
    predictors_text += (predictors_text.empty() ? "'" : ", '") + name + "'";
  if (degree > 0) predictors_text = design;
  out("%s: '%s' on %s%s; %zu rows (%zu skipped: empty cells)\n", file.c_str(), o.y.c_str(),
      fit.intercept ? "an intercept and " : "", predictors_text.c_str(), fit.n, n_missing);
  const char* method = fit.method == stats::FitMethod::kDoubleQr
                           ? "Householder QR in double precision"
                       : fit.method == stats::FitMethod::kBinary128Qr
                           ? "Householder QR in binary128 (quad) precision"
                           : "normal equations (Cholesky) in binary128 (quad) precision";
  // three digits: the condition number says how many digits are lost, not a value to reuse
  out("Least squares by %s (checked against NIST StRD); condition number of the column-scaled "
      "design %.3g\n\n",
      method, fit.condition_number);
  out("  %-20s %24s %24s %16s %16s\n", "parameter", "estimate", "std dev", "t value", "p");
  for (std::size_t k = 0; k < fit.coefficients.size(); ++k) {
    const std::string& t = tests[k].text;  // "undefined (why)" for an exact fit
    out("  %-20s %24s %24s%s\n", fit.names[k].c_str(), text_number(fit.coefficients[k]).c_str(),
        text_number(fit.standard_deviations[k]).c_str(),
        (t.rfind("undefined", 0) == 0 ? "   t " + t : t).c_str());
  }
  out("\n  residual SD = %s on %zu degrees of freedom (n = %zu, %zu parameters)\n",
      text_number(fit.residual_sd).c_str(), fit.df, fit.n, fit.coefficients.size());
  if (fit.r_squared) {
    out("  R-squared = %s (%s)\n", text_number(*fit.r_squared).c_str(), r2_definition);
  } else {
    out("  R-squared undefined (%s)\n", r2_reason.c_str());
  }
}

// --json, and --quantiles where quartiles are printed.
void add_common_options(CLI::App* cmd, StatsOptions& o, bool quantiles) {
  cmd->add_flag("--json", o.json, "one JSON object instead of text");
  if (!quantiles) return;
  cmd->add_option("--quantiles", o.quantiles,
                  "quartile definition: hf6 (Hyndman-Fan 6, NIST e-Handbook / Dataplot; default) "
                  "or hf7 (R and NumPy default)")
      ->check(CLI::IsMember({"hf6", "hf7"}));
}

}  // namespace

void register_stats_command(CLI::App& app, int& exit_code) {
  auto* stats_cmd = app.add_subcommand(
      "stats",
      "Statistics of CSV columns with the NIST e-Handbook's conventions: summaries, t / F / "
      "Levene tests, one-way ANOVA, Box-Cox lambda; least-squares regression.");
  stats_cmd->require_subcommand(1);

  // each subcommand owns its options; shared_ptr keeps them alive as long as the callbacks
  auto describe_opt = std::make_shared<StatsOptions>();
  auto* describe = stats_cmd->add_subcommand(
      "describe", "n, mean, sd, median, quartiles, IQR, min, max of one column");
  describe->add_option("file", describe_opt->files,
                       "CSV file with a header row, or a run directory (its records/*.csv)")
      ->required()
      ->expected(1);
  describe->add_option("--column,-c", describe_opt->column, "column name")->required();
  describe->add_option("--where,-w", describe_opt->where,
                       "only rows whose cell in COLUMN is VALUE: COLUMN=VALUE, repeatable, e.g. "
                       "--where platform=osmesa-llvmpipe --where kind=line --where view=3");
  describe->add_flag("--allow-incomplete", describe_opt->allow_incomplete,
                     "describe a run directory with missing shards (the output says what is "
                     "missing); without it such a run is refused with exit code 3");
  add_common_options(describe, *describe_opt, true);
  describe->callback([describe_opt, &exit_code] {
    try {
      run_describe(*describe_opt);
    } catch (const analysis::IncompleteRunError& e) {
      std::fprintf(stderr, "renderaudit stats: %s\n", e.what());
      exit_code = kExitIncomplete;
      return;
    }
    exit_code = kExitOk;
  });

  auto compare_opt = std::make_shared<StatsOptions>();
  auto* compare = stats_cmd->add_subcommand(
      "compare",
      "Compare one column of two CSV files: summaries, pooled and Welch t tests, F test, Levene "
      "tests (median, mean, 10% trimmed mean centres), Box-Cox lambda (PPCC and ML)");
  compare->add_option("files", compare_opt->files, "the two CSV files, A then B")
      ->required()
      ->expected(2);
  compare->add_option("--column,-c", compare_opt->column, "column name (in both files)")
      ->required();
  add_common_options(compare, *compare_opt, true);
  compare->callback([compare_opt, &exit_code] {
    run_compare(*compare_opt);
    exit_code = kExitOk;
  });

  auto anova_opt = std::make_shared<StatsOptions>();
  auto* anova = stats_cmd->add_subcommand(
      "anova", "One-way ANOVA of a value column grouped by another column, and Levene tests");
  anova->add_option("file", anova_opt->files, "CSV file with a header row")
      ->required()
      ->expected(1);
  anova->add_option("--group,-g", anova_opt->group, "column whose distinct texts are the groups")
      ->required();
  anova->add_option("--value,-v", anova_opt->value, "numeric column to analyse")->required();
  add_common_options(anova, *anova_opt, false);
  anova->callback([anova_opt, &exit_code] {
    run_anova(*anova_opt);
    exit_code = kExitOk;
  });

  auto regress_opt = std::make_shared<StatsOptions>();
  auto* regress = stats_cmd->add_subcommand(
      "regress",
      "Least-squares fit of one column on others, or on a polynomial in one (QR in double or "
      "binary128; checked against NIST StRD): coefficients with their standard deviations and t "
      "tests, residual SD, R-squared, the design's condition number and the method");
  regress->add_option("file", regress_opt->files, "CSV file with a header row")
      ->required()
      ->expected(1);
  regress->add_option("--y", regress_opt->y, "response column (numeric)")->required();
  auto* x_opt =
      regress->add_option("--x", regress_opt->x, "predictor column(s), comma-separated or repeated")
          ->delimiter(',');
  auto* poly_opt = regress->add_option(
      "--poly", regress_opt->poly,
      "COLUMN:DEGREE: a polynomial in one column, its powers formed in binary128 from the "
      "column's values (a CSV of rounded powers loses digits on ill-conditioned designs)");
  x_opt->excludes(poly_opt);
  poly_opt->excludes(x_opt);
  regress->add_flag("--no-intercept", regress_opt->no_intercept,
                    "fit without a constant term (R-squared is then uncentred, as NIST's)");
  add_common_options(regress, *regress_opt, false);
  regress->callback([regress_opt, &exit_code] {
    run_regress(*regress_opt);
    exit_code = kExitOk;
  });
}

}  // namespace ra::app
