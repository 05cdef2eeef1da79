// A small CSV reader for the analysis stage: a header row of column names, then rows of cells.
// - Cells are separated by commas; a cell may be enclosed in double quotes, inside which commas,
//   line breaks and doubled quotes ("") are literal. Spaces and tabs around cells are dropped
//   (util::read_csv_cell under the table rules; split_csv_line keeps them). Lines end in LF or
//   CRLF; blank lines are skipped; a UTF-8 byte order mark is ignored.
// - A line that starts with '#' is a comment and is skipped (a records file ends with its seal,
//   `# complete rows=N fnv1a64=H`); a cell that starts with '#' is quoted or not first in its row.
// - Every row must have as many cells as the header (an unexpected cell is an error, never a
//   silent shift of columns); column names must be unique.
// - An empty cell is a missing value: numeric accessors skip it and count it.
// - Numbers are parsed with std::from_chars (locale-independent, exact); "nan", "inf" and anything
//   that is not entirely a finite number is an error located by file and line.
// Every problem with the input is reported as ra::util::UserError "FILE:LINE: what is wrong".
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ra::stats {

// The values of one numeric column, in row order, without the missing (empty) cells.
struct NumericColumn {
  std::string name;
  std::vector<double> values;
  std::vector<std::size_t> rows;  // row index (0-based, not counting the header) of each value
  std::size_t n_missing = 0;      // empty cells skipped
};

// Parses a whole cell as a finite number; nullopt if it is anything else (empty included).
// A leading '+' is accepted; surrounding spaces are not (the reader has removed them).
std::optional<double> parse_number(std::string_view cell);

class CsvTable {
 public:
  // Parses CSV text. `source` names it in error messages (normally the file path).
  static CsvTable parse(std::string_view text, const std::string& source);

  // Reads and parses a file. Throws ra::util::UserError when it cannot be read or is not valid CSV.
  static CsvTable read_file(const std::string& path);

  const std::string& source() const { return source_; }
  const std::vector<std::string>& header() const { return header_; }
  std::size_t column_count() const { return header_.size(); }
  std::size_t row_count() const { return lines_.size(); }

  // Index of the column named `name`, or nullopt.
  std::optional<std::size_t> find_column(std::string_view name) const;

  // Index of the column named `name`; ra::util::UserError listing the available columns if there is none.
  std::size_t column(std::string_view name) const;

  // The cell text (unquoted) at a row (0-based, header excluded) and column.
  const std::string& cell(std::size_t row, std::size_t column) const;

  // 1-based line of the source on which a row starts.
  std::size_t line(std::size_t row) const { return lines_.at(row); }

  // The number in a cell; nullopt when the cell is empty. ra::util::UserError "FILE:LINE: column 'c':
  // 'text' is not a finite number" otherwise.
  std::optional<double> number(std::size_t row, std::size_t column) const;

  // Every number of a column (by name), skipping and counting empty cells. ra::util::UserError on an
  // unknown column or a cell that is not a number.
  NumericColumn numeric_column(std::string_view name) const;

 private:
  std::string source_;
  std::vector<std::string> header_;
  std::vector<std::string> cells_;  // row-major, column_count() per row
  std::vector<std::size_t> lines_;  // line of each row
};

}  // namespace ra::stats
