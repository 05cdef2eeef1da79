// CSV reader; see csv_table.h.
#include "stats/csv_table.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <system_error>

#include "util/cell_text.h"
#include "util/errors.h"
#include "util/zstd_stream.h"

namespace ra::stats {
namespace {

// Cells of tables that people edit: blanks around them dropped, a line end ends a row.
constexpr util::CsvRules kTableRules{true, true};

std::size_t lines_in(std::string_view text, std::size_t from, std::size_t to) {
  std::size_t n = 0;
  for (std::size_t k = from; k < to; ++k) n += text[k] == '\n';
  return n;
}

std::string located(const std::string& source, std::size_t line, const std::string& what) {
  return source + ":" + std::to_string(line) + ": " + what;
}

}  // namespace

std::optional<double> parse_number(std::string_view cell) {
  if (!cell.empty() && cell.front() == '+') {
    cell.remove_prefix(1);
    if (!cell.empty() && (cell.front() == '+' || cell.front() == '-')) return std::nullopt;
  }
  if (cell.empty()) return std::nullopt;
  double value = 0;
  const char* end = cell.data() + cell.size();
  const auto [ptr, ec] = std::from_chars(cell.data(), end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

CsvTable CsvTable::parse(std::string_view text, const std::string& source) {
  CsvTable t;
  t.source_ = source;
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);

  std::size_t line = 1;
  std::size_t i = 0;
  const std::size_t size = text.size();
  bool have_header = false;

  // one record per iteration
  while (i < size) {
    const std::size_t record_line = line;
    if (text[i] == '#') {  // a comment line (a records file's seal): skipped whole
      while (i < size && text[i] != '\n') ++i;
      if (i < size) ++i, ++line;
      continue;
    }
    std::vector<std::string> record;
    bool any_quoted = false;
    bool end_of_record = false;
    while (!end_of_record) {
      const std::size_t cell_start = i;
      bool quoted = false;
      std::string cell;
      try {
        cell = util::read_csv_cell(text, i, kTableRules, &quoted);
      } catch (const util::CsvCellError& e) {
        throw util::UserError(located(source, line + lines_in(text, cell_start, e.at), e.what()));
      }
      any_quoted = any_quoted || quoted;
      line += lines_in(text, cell_start, i);  // a quoted cell may hold line ends
      record.push_back(std::move(cell));

      // what ends the cell: a comma (another cell follows), a line end or the end of the text
      if (i < size && text[i] == ',') {
        ++i;
      } else {
        if (i < size && text[i] == '\r') ++i;
        if (i < size && text[i] == '\n') {
          ++i;
          ++line;
        } else if (i < size) {
          throw util::UserError(
              located(source, line, "a carriage return not followed by a line feed"));
        }
        end_of_record = true;
      }
    }

    const bool blank_line = record.size() == 1 && record.front().empty() && !any_quoted;
    if (blank_line) continue;
    if (!have_header) {
      for (std::size_t c = 0; c < record.size(); ++c) {
        for (std::size_t d = 0; d < c; ++d) {
          if (record[c] == record[d]) {
            throw util::UserError(
                located(source, record_line,
                        "column name '" + record[c] + "' appears twice in the header"));
          }
        }
      }
      t.header_ = std::move(record);
      have_header = true;
      continue;
    }
    if (record.size() != t.header_.size()) {
      throw util::UserError(located(source, record_line,
                                    std::to_string(record.size()) + " cells, but the header has " +
                                        std::to_string(t.header_.size()) + " columns"));
    }
    for (auto& cell : record) t.cells_.push_back(std::move(cell));
    t.lines_.push_back(record_line);
  }
  if (!have_header)
    throw util::UserError(source + ": empty file (a header row of column names is needed)");
  return t;
}

CsvTable CsvTable::read_file(const std::string& path) {
  if (util::has_zstd_extension(path)) {  // a compressed records file (rundir/records_format.h)
    try {
      return parse(util::read_zstd_file(path), path);
    } catch (const util::UserError&) {
      throw;
    } catch (const std::runtime_error& e) {
      throw util::UserError(e.what());
    }
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw util::UserError(path + ": cannot open the file for reading");
  std::ostringstream content;
  content << in.rdbuf();
  if (in.bad()) throw util::UserError(path + ": error while reading the file");
  return parse(content.str(), path);
}

std::optional<std::size_t> CsvTable::find_column(std::string_view name) const {
  for (std::size_t c = 0; c < header_.size(); ++c) {
    if (header_[c] == name) return c;
  }
  return std::nullopt;
}

std::size_t CsvTable::column(std::string_view name) const {
  if (const auto c = find_column(name)) return *c;
  std::string available;
  for (const auto& h : header_) available += (available.empty() ? "" : ", ") + h;
  throw util::UserError(source_ + ":1: no column named '" + std::string(name) +
                        "' (available: " + available + ")");
}

const std::string& CsvTable::cell(std::size_t row, std::size_t column) const {
  return cells_.at(row * header_.size() + column);
}

std::optional<double> CsvTable::number(std::size_t row, std::size_t column) const {
  const std::string& text = cell(row, column);
  if (text.empty()) return std::nullopt;
  if (auto value = parse_number(text)) return value;
  throw util::UserError(
      located(source_, line(row),
              "column '" + header_.at(column) + "': '" + text + "' is not a finite number"));
}

NumericColumn CsvTable::numeric_column(std::string_view name) const {
  const std::size_t c = column(name);
  NumericColumn out;
  out.name = std::string(name);
  for (std::size_t row = 0; row < row_count(); ++row) {
    if (const auto value = number(row, c)) {
      out.values.push_back(*value);
      out.rows.push_back(row);
    } else {
      ++out.n_missing;
    }
  }
  return out;
}

}  // namespace ra::stats
