// Values written as text cells of the project's CSV and text outputs: doubles at full precision
// and CSV escaping, and the cells of a line read back. Every writer of such files uses these, so
// that a number reads back as the same double and a name with a comma stays one cell. (Whole CSV
// files with cells over several lines, comments and located errors: stats/csv_table.h.)
#pragma once

#include <string>
#include <vector>

namespace ra::util {

// `v` with 17 significant digits ("%.17g"): parsing the text gives back the same double.
// NaN and the infinities as printf spells them: "nan", "inf", "-inf".
std::string full_precision(double v);

// The same, but "" for NaN: an empty cell means "not applicable" in the project's CSV files.
std::string full_precision_or_empty(double v);

// The same, but "" for NaN and the infinities alike.
std::string full_precision_if_finite(double v);

// One CSV cell (RFC 4180): the text unchanged unless it holds a comma, a double quote, CR or LF;
// then in double quotes with every quote doubled.
std::string csv_escape(const std::string& text);

// The cells of one CSV line (RFC 4180; the line without its line end), csv_escape's inverse: a
// cell in double quotes may hold commas and doubled quotes ("a ""b"", c" is the one cell
// a "b", c). Unquoted cells are taken as they are, blanks included. "" is one empty cell; a line
// that ends in a comma ends with an empty cell. Throws std::invalid_argument, saying what is wrong,
// on a quoted cell that is never closed, text after a closing quote, or a quote inside an unquoted
// cell.
std::vector<std::string> split_csv_line(const std::string& line);

}  // namespace ra::util
