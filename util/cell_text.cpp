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

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> cells;
  std::size_t i = 0;
  const std::size_t n = line.size();
  while (true) {
    std::string cell;
    if (i < n && line[i] == '"') {  // quoted: up to the closing quote; "" is a literal quote
      ++i;
      bool closed = false;
      while (i < n) {
        const char c = line[i++];
        if (c != '"') {
          cell += c;
        } else if (i < n && line[i] == '"') {
          cell += '"';
          ++i;
        } else {
          closed = true;
          break;
        }
      }
      if (!closed) throw std::invalid_argument("a quoted cell is never closed");
      if (i < n && line[i] != ',')
        throw std::invalid_argument(
            "text after a quoted cell (a quote inside a quoted cell is written \"\")");
    } else {
      const std::size_t start = i;
      while (i < n && line[i] != ',') {
        if (line[i] == '"')
          throw std::invalid_argument(
              "a double quote inside an unquoted cell (quote the whole cell and write the quote "
              "as \"\")");
        ++i;
      }
      cell = line.substr(start, i - start);
    }
    cells.push_back(std::move(cell));
    if (i >= n) return cells;
    ++i;  // the comma: another cell follows
  }
}

}  // namespace ra::util
