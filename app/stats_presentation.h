// How `renderaudit stats` presents its results (stats_command.cpp computes them): numbers in
// JSON and text, the descriptions' table, tests that may be undefined for the data (a null with a
// "reason" in JSON, "undefined (...)" in text), Box-Cox, and the header of every JSON answer.
#pragma once

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "stats/box_cox.h"
#include "stats/descriptive.h"
#include "stats/hypothesis_tests.h"

namespace ra::app::stats_presentation {

using nlohmann::json;

// The schema version of the JSON answers.
constexpr int kSchemaVersion = 1;

// A result that is not representable in double precision (a sum of squares of data near 1e200 is
// near 1e400) is written as a string saying so, never as NaN or inf: the statistics that matter
// (t, F, p, sd) are computed on scaled data and are always finite.
constexpr const char* kOutOfRange = "out of double range (|x| > 1.8e308)";
// A number for JSON. The statistics library never returns a non-finite value; if it ever did, that
// is a bug to report loudly, not a NaN to print.
json number(double x);
// printf-style text to std::cout (one stream for text and JSON, so tests can capture both).
void out(const char* format, ...) __attribute__((format(printf, 1, 2)));
// A number for text: 10 significant digits (%.10g), kOutOfRange for an infinity.
std::string text_number(double x);

json description_json(const stats::Description& d);
// The descriptions side by side, one column each under its title, one row per statistic.
void print_description_rows(const std::vector<stats::Description>& ds,
                            const std::vector<std::string>& titles);

// A test that may be undefined for the data: its JSON and its text line.
struct Reported {
  json j;
  std::string text;
};

// fill(compute(), r), or where compute throws std::invalid_argument: `null_keys` null and the
// reason, in JSON and text.
template <typename Compute, typename Fill>
Reported report_test(const std::vector<std::string>& null_keys, Compute compute, Fill fill) {
  Reported r;
  try {
    fill(compute(), r);
  } catch (const std::invalid_argument& e) {
    r.j = json::object();
    for (const auto& k : null_keys) r.j[k] = nullptr;
    r.j["reason"] = e.what();
    r.text = std::string("undefined (") + e.what() + ")";
  }
  return r;
}

// The two-sample t test (pooled or Welch).
Reported t_report(const std::vector<double>& a, const std::vector<double>& b, bool pooled);
// An F statistic as `symbol` = value, df = (df1, df2), p = p.
void fill_f(const stats::FTestResult& f, Reported& r, const char* symbol);
// Levene's test with each centre: JSON object keyed by centre, and text lines.
json levene_reports(const std::vector<std::vector<double>>& groups, std::string& text);
json box_cox_json(const stats::BoxCoxResult& b);
std::string box_cox_text(const stats::BoxCoxResult& b);
// The JSON answer, indented by 2.
void print_json(const json& j);
// The document header of a `stats COMMAND --json` answer.
json header_json(const char* command);

}  // namespace ra::app::stats_presentation
