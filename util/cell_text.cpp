// Text cells: full-precision doubles and CSV escaping (cell_text.h).
#include "util/cell_text.h"

#include <cmath>
#include <cstdio>

namespace ra::util {

std::string full_precision(double v) {
  char buf[32];  // "-1.2345678901234567e-308": 24 characters at most
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string full_precision_or_empty(double v) {
  return std::isnan(v) ? std::string() : full_precision(v);
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

}  // namespace ra::util
