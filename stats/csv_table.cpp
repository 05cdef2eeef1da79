// CSV reader; see csv_table.h.
#include "stats/csv_table.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <system_error>

#include "util/errors.h"
#include "util/zstd_stream.h"

namespace ra::stats {
namespace {

bool is_blank(char c) { return c == ' ' || c == '\t'; }

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
      std::string cell;
      while (i < size && is_blank(text[i])) ++i;
      if (i < size && text[i] == '"') {
        // quoted cell: up to the closing quote; "" is a literal quote
        any_quoted = true;
        const std::size_t open_line = line;
        ++i;
        bool closed = false;
        while (i < size) {
          const char c = text[i++];
          if (c == '"') {
            if (i < size && text[i] == '"') {
              cell += '"';
              ++i;
            } else {
              closed = true;
              break;
            }
          } else {
            if (c == '\n') ++line;
            cell += c;
          }
        }
        if (!closed) {
          throw util::UserError(located(source, open_line, "a quoted cell is never closed"));
        }
        while (i < size && is_blank(text[i])) ++i;
        if (i < size && text[i] != ',' && text[i] != '\n' && text[i] != '\r') {
          throw util::UserError(
              located(source, line,
                      "unexpected text after a quoted cell (a quote inside a quoted "
                      "cell is written \"\")"));
        }
      } else {
        const std::size_t start = i;
        while (i < size && text[i] != ',' && text[i] != '\n' && text[i] != '\r') {
          if (text[i] == '"') {
            throw util::UserError(
                located(source, line,
                        "a double quote inside an unquoted cell (quote the whole cell "
                        "and write the quote as \"\")"));
          }
          ++i;
        }
        std::size_t stop = i;
        while (stop > start && is_blank(text[stop - 1])) --stop;
        cell.assign(text.substr(start, stop - start));
      }
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
