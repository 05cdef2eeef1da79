// Values written as text cells of the project's CSV and text outputs: doubles at full precision
// and CSV escaping. Every writer of such files uses these, so that a number reads back as the same
// double and a name with a comma stays one cell.
#pragma once

#include <string>

namespace ra::util {

// `v` with 17 significant digits ("%.17g"): parsing the text gives back the same double.
// NaN and the infinities as printf spells them: "nan", "inf", "-inf".
std::string full_precision(double v);

// The same, but "" for NaN: an empty cell means "not applicable" in the project's CSV files.
std::string full_precision_or_empty(double v);

// One CSV cell (RFC 4180): the text unchanged unless it holds a comma, a double quote, CR or LF;
// then in double quotes with every quote doubled.
std::string csv_escape(const std::string& text);

}  // namespace ra::util
