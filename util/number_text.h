// Numbers written as text for people: tables, notes, figure labels, summaries. Every such text
// asks these (full-precision cells that must read back as the same double: cell_text.h). They are
// printf's conversions, so the text is what `printf FORMAT` gives: "%.4g" of 0.000123456 is
// "0.0001235", of 1234567 "1.235e+06"; NaN and the infinities are "nan", "inf", "-inf" (callers
// that write something else for them say so where they call).
#pragma once

#include <cstdarg>
#include <string>

namespace ra::util {

// `v` through a printf format of one double ("%.4g", "%.2f", "%+.1f%%"); never truncated.
std::string format_double(const char* format, double v);

// `v` through `format` as format_double, "" when `v` is NaN (an empty table cell; the infinities
// are still written).
std::string format_double_or_empty(const char* format, double v);

// printf into a string of any length: format_text("%s: %d", name, n).
std::string format_text(const char* format, ...) __attribute__((format(printf, 1, 2)));
std::string format_text_v(const char* format, va_list args);

// `v` with `digits` significant digits, trailing zeros dropped ("%.*g"): significant(1.5, 4) is
// "1.5", significant(123456, 4) "1.235e+05". significant(v, 6) is printf's plain "%g".
std::string significant(double v, int digits);

// `v` with `decimals` digits after the point ("%.*f"): fixed(2.0 / 3, 2) is "0.67".
std::string fixed(double v, int decimals);

// A count with its thousands grouped by commas, as the summaries print them: 64000 is "64,000".
std::string grouped(unsigned long long n);

}  // namespace ra::util
