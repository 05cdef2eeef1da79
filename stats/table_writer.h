// One table model, three renderings: CSV (for programs), Markdown (for reading and for the
// terminal) and LaTeX (for a paper). Every table the analysis stage writes goes through here, so a
// number is formatted once and the three files cannot disagree.
//
// Conventions:
// - A cell has the text shown in Markdown and LaTeX (numbers rounded to the table's decimals, as
//   the paper prints them) and, for numbers, a CSV text with 9 significant digits so that programs
//   reading the CSV lose nothing that matters. Counts are exact everywhere.
// - Non-finite numbers are never formatted: number_cell() throws std::logic_error on one. A value
//   that does not exist is a text cell saying why ("no data", "undefined").
// - CSV: RFC 4180 quoting (cells holding a comma, quote or line break are quoted, quotes doubled);
//   the title and notes come first as lines starting with "# " (pandas: comment='#'; R:
//   comment.char='#'), then one header row; spanning group labels are joined to the column names
//   ("osmesa-llvmpipe median").
// - Markdown: a "### title" heading, a pipe table (group labels joined to column names as in CSV,
//   '|' in cells escaped), then the notes as a list (title and notes are written as they are).
// - LaTeX: a table environment with booktabs rules (\usepackage{booktabs}), spanning group labels
//   as \multicolumn with \cmidrule, the title as caption, notes in \footnotesize below; special
//   characters escaped, and the scale notation "x10^k" of titles and notes set as $\times 10^{k}$.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "util/cell_text.h"

namespace ra::stats {

struct TableCell {
  std::string text;  // Markdown and LaTeX
  std::string csv;   // CSV; empty means: the same as text
};

// A text cell (identical in all three renderings).
TableCell text_cell(std::string text);
// A number rounded to `decimals` places for reading ("-0.00" is written "0.00"), 9 significant
// digits in CSV. Throws std::logic_error when `value` is not finite.
TableCell number_cell(double value, int decimals);
// A number with `significant` significant digits for reading (p-values, statistics), 9 in CSV.
TableCell significant_cell(double value, int significant = 3);
// An exact count.
TableCell count_cell(std::uint64_t n);
// k of n as a percentage with its Clopper-Pearson 95% interval, "97.50 (97.10-97.86)"; CSV: the
// percentage alone (stats/binomial_interval.h). n = 0 reads "0.00 (0.00-100.00)".
TableCell share_cell(std::uint64_t k, std::uint64_t n);

// "%.*f" without the sign of a zero; throws std::logic_error on a non-finite value.
std::string format_fixed(double value, int decimals);
// "%.*g"; throws std::logic_error on a non-finite value.
std::string format_significant(double value, int significant);

// A column's alignment. In Markdown: kLeft ":---", kRight "---:", kCenter ":---:", kDefault "---"
// (the reader's default, left); in LaTeX l, r, c, l.
enum class Align { kLeft, kRight, kCenter, kDefault };

struct TableColumn {
  std::string name;
  Align align = Align::kRight;
};

// A label spanning `span` consecutive columns in a header row above the column names (the paper's
// "Platform I" over "Median IQR"); an empty label spans columns that have none.
struct ColumnGroup {
  std::string label;
  std::size_t span = 1;
};

struct Table {
  std::string file_stem;  // file name without extension, e.g. "table03_pe"; [a-z0-9_] (LaTeX label)
  std::string title;      // one line: what the table mirrors, the metric, units, scale, quartiles
  std::string latex_title;          // the title in LaTeX; empty: the title, escaped
  std::vector<std::string> notes;   // one sentence each, plain text
  std::vector<ColumnGroup> groups;  // empty, or spans adding up to columns.size()
  std::vector<TableColumn> columns;
  std::vector<std::vector<TableCell>> rows;  // each exactly columns.size() cells
  std::vector<std::size_t> rules_before;     // row indices preceded by a rule (LaTeX \midrule)
};

// Appends columns named `names`, each aligned `align`, to `table.columns`.
void add_columns(Table& table, const std::vector<std::string>& names, Align align);

// Throws std::logic_error when the table is inconsistent (row width, group spans).
void check_table(const Table& table);

std::string render_csv(const Table& table);
std::string render_markdown(const Table& table);
std::string render_latex(const Table& table);

// A Markdown table written a row at a time between paragraphs (the studies' documents, the audit's
// report), spelled as render_markdown spells its tables: markdown_header gives the header row and
// the alignment row, markdown_row one row ("| a | b |\n"); every cell through markdown_escape.
std::string markdown_header(const std::vector<std::string>& names, const std::vector<Align>& align);
// The first `left_columns` columns kDefault ("---"), the others kRight.
std::string markdown_header(const std::vector<std::string>& names, std::size_t left_columns);
std::string markdown_row(const std::vector<std::string>& cells);
// The alignment row alone ("| :--- | ---: |\n"), below a header row that is not a row of names
// (cells spelled by the caller). markdown_compact_rule: `columns` kDefault columns spelled without
// blanks ("|---|---|\n"), as the run summary writes its table.
std::string markdown_rule(const std::vector<Align>& align);
std::string markdown_compact_rule(std::size_t columns);

// Escapes for one cell / text fragment (CSV: util/cell_text.h).
std::string markdown_escape(const std::string& text);
std::string latex_escape(const std::string& text);

}  // namespace ra::stats
