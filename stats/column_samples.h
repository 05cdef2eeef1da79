// The data `renderaudit stats` computes on, read from CSV columns (csv_table.h): one column's
// values (all rows, or the rows meeting COLUMN=VALUE conditions), one column's values grouped by
// another's labels (ANOVA), and a response with its predictors from the rows complete in all of
// them (least squares). The command (app/stats_command.cpp) only chooses and prints.
// Every problem with the input is a ra::util::UserError naming the file (or the run) and the
// column, with what is needed.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "stats/csv_table.h"

namespace ra::stats {

// A numeric column's values, and the empty cells skipped. `file` names where they came from (a
// file, or a run's records: "RUN/records (N files)").
struct ColumnSample {
  std::string file;
  std::string column;
  std::vector<double> values;
  std::size_t n_missing = 0;
};

// `column` of a CSV file, with at least two values.
ColumnSample read_column_sample(const std::string& file, const std::string& column);

// COLUMN=VALUE conditions on a row: the cell of COLUMN reads VALUE exactly.
using RowConditions = std::vector<std::pair<std::string, std::string>>;
// The conditions as typed ("platform=osmesa-llvmpipe"); an empty column name or no '=' stops.
RowConditions parse_row_conditions(const std::vector<std::string>& where);

// Adds to `sample` the values of `sample.column` in the rows of `file` meeting every condition;
// their empty cells to its n_missing.
void add_selected_values(const std::string& file, const RowConditions& conditions,
                         ColumnSample& sample);
// Stops unless `sample` holds at least two values of the rows selected.
void require_two_selected_values(const ColumnSample& sample);

// The values of `value_column` grouped by the label in `group_column`, groups in order of first
// appearance; rows whose label or value is empty are skipped and counted. At least 2 groups and
// more values than groups (one-way ANOVA), else it stops naming `file`.
struct GroupedValues {
  std::vector<std::string> names;
  std::vector<std::vector<double>> groups;
  std::size_t n = 0;          // values in all groups
  std::size_t n_missing = 0;  // rows skipped
};
GroupedValues read_grouped_values(const std::string& file, const std::string& group_column,
                                  const std::string& value_column);

// "COLUMN:DEGREE" of a polynomial fit -> the column and the degree (1..kMaxPolynomialDegree).
constexpr int kMaxPolynomialDegree = 30;
std::pair<std::string, int> parse_polynomial_spec(const std::string& file, const std::string& spec);

// The predictors' names checked: none empty, none twice, none the response `y`.
void check_predictor_names(const std::string& file, const std::vector<std::string>& columns,
                           const std::string& y);

// The response and the predictors (x[j] parallel to y) from the rows where every one of them is
// a number; rows with an empty cell in any are skipped and counted (a cell that is not a number
// stops with file:line, CsvTable::number).
struct RegressionData {
  std::vector<double> y;
  std::vector<std::vector<double>> x;
  std::size_t n_missing = 0;
};
RegressionData read_regression_data(const std::string& file, const std::string& y,
                                    const std::vector<std::string>& x);

}  // namespace ra::stats
