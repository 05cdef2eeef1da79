// Text cells: full-precision doubles, CSV escaping and the cells of a line (cell_text.h).
#include "util/cell_text.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace ra::util {

std::string full_precision(double v) {
  char buf[32];  // "-1.2345678901234567e-308": 24 characters at most
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string full_precision_or_empty(double v) {
  return std::isnan(v) ? std::string() : full_precision(v);
}

std::string full_precision_if_finite(double v) {
  return std::isfinite(v) ? full_precision(v) : std::string();
}

std::string csv_escape(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string s = "\"";
  for (char c : text) {
    if (c == '"') s += '"';
    s += c;
  }
  return s + "\"";
}

namespace {

bool is_blank(char c) { return c == ' ' || c == '\t'; }

}  // namespace

std::string read_csv_cell(std::string_view text, std::size_t& pos, CsvRules rules, bool* quoted) {
  const std::size_t n = text.size();
  const auto ends_cell = [&](char c) {
    return c == ',' || (rules.line_ends_end_cells && (c == '\n' || c == '\r'));
  };
  if (rules.trim_blanks)
    while (pos < n && is_blank(text[pos])) ++pos;
  std::string cell;
  if (quoted) *quoted = pos < n && text[pos] == '"';
  if (pos < n && text[pos] == '"') {  // quoted: up to the closing quote; "" is a literal quote
    const std::size_t open = pos++;
    bool closed = false;
    while (pos < n) {
      const char c = text[pos++];
      if (c != '"') {
        cell += c;
      } else if (pos < n && text[pos] == '"') {
        cell += '"';
        ++pos;
      } else {
        closed = true;
        break;
      }
    }
    if (!closed) throw CsvCellError("a quoted cell is never closed", open);
    if (rules.trim_blanks)
      while (pos < n && is_blank(text[pos])) ++pos;
    if (pos < n && !ends_cell(text[pos]))
      throw CsvCellError(
          "unexpected text after a quoted cell (a quote inside a quoted cell is written \"\")",
          pos);
    return cell;
  }
  const std::size_t start = pos;
  while (pos < n && !ends_cell(text[pos])) {
    if (text[pos] == '"')
      throw CsvCellError(
          "a double quote inside an unquoted cell (quote the whole cell and write the quote as "
          "\"\")",
          pos);
    ++pos;
  }
  std::size_t stop = pos;
  if (rules.trim_blanks)
    while (stop > start && is_blank(text[stop - 1])) --stop;
  return std::string(text.substr(start, stop - start));
}

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> cells;
  std::size_t pos = 0;
  while (true) {
    cells.push_back(read_csv_cell(line, pos, CsvRules{}));
    if (pos >= line.size()) return cells;
    ++pos;  // the comma: another cell follows
  }
}

}  // namespace ra::util
