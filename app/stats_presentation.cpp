// How `renderaudit stats` presents its results; see stats_presentation.h.
#include "app/stats_presentation.h"

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <iostream>

#include "rundir/manifest.h"
#include "util/number_text.h"

namespace ra::app::stats_presentation {

json number(double x) {
  if (std::isnan(x)) throw std::logic_error("stats: internal error: a NaN result");
  if (!std::isfinite(x)) return kOutOfRange;
  return x;
}

void out(const char* format, ...) {
  va_list args;
  va_start(args, format);
  std::cout << util::format_text_v(format, args);
  va_end(args);
}

std::string text_number(double x) {
  if (std::isinf(x)) return kOutOfRange;
  return util::significant(x, 10);
}

json description_json(const stats::Description& d) {
  return json{{"n", d.n},
              {"mean", number(d.mean)},
              {"sd", number(d.sd)},
              {"median", number(d.median)},
              {"q1", number(d.q1)},
              {"q3", number(d.q3)},
              {"iqr", number(d.iqr)},
              {"min", number(d.min)},
              {"max", number(d.max)}};
}

void print_description_rows(const std::vector<stats::Description>& ds,
                            const std::vector<std::string>& titles) {
  out("%-8s", "");
  for (const auto& t : titles) out(" %24s", t.c_str());
  out("\n");
  const auto row = [&](const char* name, auto field) {
    out("%-8s", name);
    for (const auto& d : ds) out(" %24s", field(d).c_str());
    out("\n");
  };
  row("n", [](const stats::Description& d) { return std::to_string(d.n); });
  row("mean", [](const stats::Description& d) { return text_number(d.mean); });
  row("sd", [](const stats::Description& d) { return text_number(d.sd); });
  row("median", [](const stats::Description& d) { return text_number(d.median); });
  row("q1", [](const stats::Description& d) { return text_number(d.q1); });
  row("q3", [](const stats::Description& d) { return text_number(d.q3); });
  row("iqr", [](const stats::Description& d) { return text_number(d.iqr); });
  row("min", [](const stats::Description& d) { return text_number(d.min); });
  row("max", [](const stats::Description& d) { return text_number(d.max); });
}

Reported t_report(const std::vector<double>& a, const std::vector<double>& b, bool pooled) {
  return report_test(
      {"statistic", "df", "p_value"},
      [&] { return pooled ? stats::t_test_pooled(a, b) : stats::t_test_welch(a, b); },
      [](const stats::TTestResult& t, Reported& r) {
        r.j = json{{"statistic", number(t.statistic)},
                   {"df", number(t.df)},
                   {"p_value", number(t.p_value)},
                   {"mean_difference", number(t.mean_difference)},
                   {"standard_error", number(t.standard_error)}};
        if (t.pooled_sd) r.j["pooled_sd"] = number(*t.pooled_sd);
        r.text = "t = " + text_number(t.statistic) + ", df = " + text_number(t.df) +
                 ", p = " + text_number(t.p_value);
      });
}

void fill_f(const stats::FTestResult& f, Reported& r, const char* symbol) {
  r.j = json{{"statistic", number(f.statistic)},
             {"df1", number(f.df1)},
             {"df2", number(f.df2)},
             {"p_value", number(f.p_value)}};
  r.text = std::string(symbol) + " = " + text_number(f.statistic) + ", df = (" +
           text_number(f.df1) + ", " + text_number(f.df2) + "), p = " + text_number(f.p_value);
}

json levene_reports(const std::vector<std::vector<double>>& groups, std::string& text) {
  json j = json::object();
  for (const auto center : {stats::LeveneCenter::kMedian, stats::LeveneCenter::kMean,
                            stats::LeveneCenter::kTrimmedMean}) {
    const Reported r = report_test(
        {"statistic", "df1", "df2", "p_value"}, [&] { return stats::levene_test(groups, center); },
        [](const stats::FTestResult& f, Reported& r) { fill_f(f, r, "W"); });
    j[stats::levene_center_name(center)] = r.j;
    char label[64];
    std::snprintf(
        label, sizeof label, "  %-28s: ",
        (std::string("Levene (") + stats::levene_center_name(center) + " centre)").c_str());
    text += label + r.text + "\n";
  }
  return j;
}

json box_cox_json(const stats::BoxCoxResult& b) {
  json j{{"method", stats::box_cox_method_name(b.method)},
         {"applicable", b.applicable},
         {"n", b.n},
         {"shift", number(b.shift)}};
  if (!b.applicable) {
    j["lambda"] = nullptr;
    j["reason"] = b.reason;
    return j;
  }
  j["lambda"] = number(b.lambda);
  j[b.method == stats::BoxCoxMethod::kPpcc ? "correlation" : "log_likelihood"] =
      number(b.objective);
  j["ppcc_at_lambda"] = number(b.ppcc_at_lambda);
  j["at_boundary"] = b.at_boundary;
  return j;
}

std::string box_cox_text(const stats::BoxCoxResult& b) {
  if (!b.applicable) return "not applicable (" + b.reason + ")";
  std::string s = "lambda = " + text_number(b.lambda);
  s += b.method == stats::BoxCoxMethod::kPpcc ? ", correlation = " : ", log-likelihood = ";
  s += text_number(b.objective);
  if (b.shift != 0) s += ", data shifted by " + text_number(b.shift);
  if (b.at_boundary) s += " (at the end of the search range [-2, 2])";
  return s;
}

void print_json(const json& j) { std::cout << j.dump(2) << "\n"; }

json header_json(const char* command) {
  json j = rundir::document_header("stats", kSchemaVersion, false);
  j["command"] = command;
  return j;
}

}  // namespace ra::app::stats_presentation
