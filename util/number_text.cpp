// Numbers written as text for people; see number_text.h.
#include "util/number_text.h"

#include <cmath>
#include <cstdarg>
#include <cstdio>

namespace ra::util {

std::string format_double(const char* format, double v) {
  char buf[64];
  const int n = std::snprintf(buf, sizeof buf, format, v);
  if (n < 0) return "";
  if (static_cast<std::size_t>(n) < sizeof buf) return std::string(buf, static_cast<std::size_t>(n));
  std::string text(static_cast<std::size_t>(n) + 1, '\0');  // "%f" of 1e300: 300 digits and more
  std::snprintf(text.data(), text.size(), format, v);
  text.pop_back();
  return text;
}

std::string format_double_or_empty(const char* format, double v) {
  return std::isnan(v) ? std::string() : format_double(format, v);
}

std::string format_text(const char* format, ...) {
  va_list args;
  va_start(args, format);
  std::string text = format_text_v(format, args);
  va_end(args);
  return text;
}

std::string format_text_v(const char* format, va_list args) {
  va_list again;
  va_copy(again, args);
  const int n = std::vsnprintf(nullptr, 0, format, args);
  std::string text(static_cast<std::size_t>(n > 0 ? n : 0) + 1, '\0');
  std::vsnprintf(text.data(), text.size(), format, again);
  va_end(again);
  text.pop_back();
  return text;
}

std::string significant(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);  // at most 17 + 7 characters for digits <= 17
  return buf;
}

std::string fixed(double v, int decimals) {
  const int n = std::snprintf(nullptr, 0, "%.*f", decimals, v);
  std::string text(static_cast<std::size_t>(n > 0 ? n : 0) + 1, '\0');
  std::snprintf(text.data(), text.size(), "%.*f", decimals, v);
  text.pop_back();
  return text;
}

std::string grouped(unsigned long long n) {
  std::string digits = std::to_string(n), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

}  // namespace ra::util
