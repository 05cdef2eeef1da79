// Values written as text cells of the project's CSV and text outputs: doubles at full precision
// and CSV escaping, and the cells of a line read back. Every writer of such files uses these, so
// that a number reads back as the same double and a name with a comma stays one cell. (Whole CSV
// files with a header, comments and located errors: stats/csv_table.h, on the same cell reader.)
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
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

// The two ways the project's CSV readers treat what lies around and between cells.
struct CsvRules {
  // Spaces and tabs around a cell (outside its quotes) are dropped: tables that people edit
  // (stats/csv_table.h). Kept, as Python's csv.reader keeps them: lines the project wrote itself.
  bool trim_blanks = false;
  // CR and LF end an unquoted cell (and its row): whole files read at once. Otherwise they are
  // ordinary characters: a line already cut from its file.
  bool line_ends_end_cells = false;
};

// What read_csv_cell found wrong, and where: `at` is the offset in the text of the opening quote
// of a cell never closed, of the text after a closing quote, or of a stray quote.
struct CsvCellError : std::invalid_argument {
  CsvCellError(const char* what, std::size_t at) : std::invalid_argument(what), at(at) {}
  std::size_t at;
};

// One cell of CSV text (RFC 4180) read from `pos`: a cell in double quotes may hold commas, line
// ends and doubled quotes ("a ""b"", c" is the one cell a "b", c); an unquoted cell is taken as
// it is (blanks as `rules` say) up to a comma, a line end (as `rules` say) or the end. `pos` is
// left on what ended the cell. `quoted` says whether it was in quotes. Throws CsvCellError on a
// quoted cell never closed, text after a closing quote, or a quote inside an unquoted cell.
std::string read_csv_cell(std::string_view text, std::size_t& pos, CsvRules rules,
                          bool* quoted = nullptr);

// The cells of one CSV line (the line without its line end), csv_escape's inverse: read_csv_cell
// with blanks kept and CR and LF ordinary characters. "" is one empty cell; a line that ends in a
// comma ends with an empty cell. Throws std::invalid_argument (a CsvCellError) as read_csv_cell.
std::vector<std::string> split_csv_line(const std::string& line);

}  // namespace ra::util
