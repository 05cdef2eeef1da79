// The data of `renderaudit stats`, read from CSV columns (column_samples.h).
#include "stats/column_samples.h"

#include <map>
#include <optional>
#include <set>
#include <stdexcept>

#include "util/errors.h"

namespace ra::stats {

ColumnSample read_column_sample(const std::string& file, const std::string& column) {
  const CsvTable table = CsvTable::read_file(file);
  NumericColumn c = table.numeric_column(column);
  if (c.values.size() < 2) {
    throw util::UserError(
        file + ": column '" + column + "' has " + std::to_string(c.values.size()) + " value(s) (" +
        std::to_string(c.n_missing) + " empty cells skipped); at least 2 are needed");
  }
  return ColumnSample{file, column, std::move(c.values), c.n_missing};
}

RowConditions parse_row_conditions(const std::vector<std::string>& where) {
  RowConditions conditions;
  for (const std::string& w : where) {
    const std::size_t eq = w.find('=');
    if (eq == std::string::npos || eq == 0)
      throw util::UserError("--where '" + w +
                            "': expected COLUMN=VALUE, e.g. platform=osmesa-llvmpipe");
    conditions.emplace_back(w.substr(0, eq), w.substr(eq + 1));
  }
  return conditions;
}

void add_selected_values(const std::string& file, const RowConditions& conditions,
                         ColumnSample& sample) {
  const CsvTable t = CsvTable::read_file(file);
  const std::size_t col = t.column(sample.column);
  std::vector<std::pair<std::size_t, std::string>> conds;
  for (const auto& [c, v] : conditions) conds.emplace_back(t.column(c), v);
  for (std::size_t r = 0; r < t.row_count(); ++r) {
    bool keep = true;
    for (const auto& [c, v] : conds) keep = keep && t.cell(r, c) == v;
    if (!keep) continue;
    if (const std::optional<double> x = t.number(r, col))
      sample.values.push_back(*x);
    else
      ++sample.n_missing;
  }
}

void require_two_selected_values(const ColumnSample& s) {
  if (s.values.size() < 2)
    throw util::UserError(s.file + ": column '" + s.column + "' has " +
                          std::to_string(s.values.size()) + " value(s) in the rows selected (" +
                          std::to_string(s.n_missing) +
                          " empty cells skipped); at least 2 are needed");
}

GroupedValues read_grouped_values(const std::string& file, const std::string& group_column,
                                  const std::string& value_column) {
  const CsvTable table = CsvTable::read_file(file);
  const std::size_t group_at = table.column(group_column);
  const std::size_t value_at = table.column(value_column);
  GroupedValues out;
  std::map<std::string, std::size_t> index;
  for (std::size_t row = 0; row < table.row_count(); ++row) {
    const std::string& label = table.cell(row, group_at);
    const std::optional<double> value = table.number(row, value_at);
    if (label.empty() || !value) {
      ++out.n_missing;
      continue;
    }
    auto [it, inserted] = index.emplace(label, out.names.size());
    if (inserted) {
      out.names.push_back(label);
      out.groups.emplace_back();
    }
    out.groups[it->second].push_back(*value);
  }
  for (const auto& g : out.groups) out.n += g.size();
  if (out.groups.size() < 2 || out.n <= out.groups.size()) {
    throw util::UserError(file + ": column '" + group_column + "' gives " +
                          std::to_string(out.groups.size()) + " group(s) with " +
                          std::to_string(out.n) + " value(s) of '" + value_column +
                          "'; ANOVA needs at least 2 groups and more values than groups");
  }
  return out;
}

std::pair<std::string, int> parse_polynomial_spec(const std::string& file,
                                                  const std::string& spec) {
  const auto colon = spec.rfind(':');
  const std::string column = colon == std::string::npos ? "" : spec.substr(0, colon);
  const std::string degree = colon == std::string::npos ? "" : spec.substr(colon + 1);
  int d = 0;
  std::size_t used = 0;
  try {
    d = std::stoi(degree, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (column.empty() || used == 0 || used != degree.size() || d < 1 || d > kMaxPolynomialDegree) {
    throw util::UserError(file + ": --poly '" + spec +
                          "' is not COLUMN:DEGREE with a column name and "
                          "a degree from 1 to " +
                          std::to_string(kMaxPolynomialDegree) +
                          " (e.g. --poly x:10 fits x, x^2, ..., x^10)");
  }
  return {column, d};
}

void check_predictor_names(const std::string& file, const std::vector<std::string>& columns,
                           const std::string& y) {
  std::set<std::string> seen;
  for (const auto& name : columns) {
    if (name.empty()) throw util::UserError(file + ": --x has an empty column name");
    if (!seen.insert(name).second) {
      throw util::UserError(file + ": --x names column '" + name +
                            "' twice; each predictor may appear once");
    }
    if (name == y) {
      throw util::UserError(file + ": column '" + name +
                            "' is both the response (--y) and a predictor (--x or --poly)");
    }
  }
}

RegressionData read_regression_data(const std::string& file, const std::string& y,
                                    const std::vector<std::string>& x) {
  const CsvTable table = CsvTable::read_file(file);
  const std::size_t y_column = table.column(y);
  std::vector<std::size_t> x_columns;
  for (const auto& name : x) x_columns.push_back(table.column(name));
  RegressionData out;
  out.x.resize(x.size());
  std::vector<double> row_x(x.size());
  for (std::size_t row = 0; row < table.row_count(); ++row) {
    const std::optional<double> value = table.number(row, y_column);
    bool complete = value.has_value();
    for (std::size_t j = 0; j < x_columns.size(); ++j) {
      const std::optional<double> v = table.number(row, x_columns[j]);
      if (v) row_x[j] = *v;
      complete = complete && v.has_value();
    }
    if (!complete) {
      ++out.n_missing;
      continue;
    }
    out.y.push_back(*value);
    for (std::size_t j = 0; j < row_x.size(); ++j) out.x[j].push_back(row_x[j]);
  }
  return out;
}

}  // namespace ra::stats
