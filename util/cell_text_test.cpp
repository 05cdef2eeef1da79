// Tests of the text cells (cell_text.h). Expected texts are CPython's ("%.17g" % x, and
// csv.writer's QUOTE_MINIMAL cell, with /usr/bin/python3), not this code's.
#include "util/cell_text.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace ra::util {
namespace {

TEST(CellText, FullPrecisionMatchesPython) {
  EXPECT_EQ(full_precision(0.1), "0.10000000000000001");
  EXPECT_EQ(full_precision(1.0 / 3.0), "0.33333333333333331");
  EXPECT_EQ(full_precision(-2.5e-308), "-2.4999999999999998e-308");
  EXPECT_EQ(full_precision(1e300), "1.0000000000000001e+300");
  EXPECT_EQ(full_precision(123456789.125), "123456789.125");
  EXPECT_EQ(full_precision(5e-324), "4.9406564584124654e-324");  // the smallest subnormal
  EXPECT_EQ(full_precision(-0.0), "-0");
  EXPECT_EQ(full_precision(std::nan("")), "nan");
  EXPECT_EQ(full_precision(-std::numeric_limits<double>::infinity()), "-inf");
}

// 17 significant digits are enough for every double (IEEE 754 binary64): the text parses back to
// the same bits, also for random bit patterns across the whole exponent range.
TEST(CellText, FullPrecisionRoundTrips) {
  std::mt19937_64 gen(7);
  for (int i = 0; i < 20000; ++i) {
    const uint64_t bits = gen();
    double v;
    std::memcpy(&v, &bits, sizeof v);
    if (!std::isfinite(v)) continue;
    EXPECT_EQ(std::strtod(full_precision(v).c_str(), nullptr), v) << full_precision(v);
  }
}

TEST(CellText, FullPrecisionOrEmptyLeavesOnlyNaNEmpty) {
  EXPECT_EQ(full_precision_or_empty(std::nan("")), "");
  EXPECT_EQ(full_precision_or_empty(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(full_precision_or_empty(2.5), "2.5");
}

TEST(CellText, CsvEscapeMatchesPythonCsv) {
  EXPECT_EQ(csv_escape("plain"), "plain");
  EXPECT_EQ(csv_escape(" lead"), " lead");  // spaces need no quotes
  EXPECT_EQ(csv_escape("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_escape("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csv_escape("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(csv_escape("cr\rx"), "\"cr\rx\"");
}

using Cells = std::vector<std::string>;

// Lines and their cells as Python's csv.reader gives them (list(csv.reader([line]))[0]).
TEST(CellText, SplitCsvLineMatchesPythonCsv) {
  EXPECT_EQ(split_csv_line("a,b,c"), (Cells{"a", "b", "c"}));
  EXPECT_EQ(split_csv_line("a,,c"), (Cells{"a", "", "c"}));
  EXPECT_EQ(split_csv_line("a,b,"), (Cells{"a", "b", ""}));  // a trailing comma: an empty cell
  EXPECT_EQ(split_csv_line(",a"), (Cells{"", "a"}));
  EXPECT_EQ(split_csv_line(" a , b"), (Cells{" a ", " b"}));  // blanks kept
  EXPECT_EQ(split_csv_line("\"a,b\",c"), (Cells{"a,b", "c"}));
  EXPECT_EQ(split_csv_line("\"say \"\"hi\"\"\",x"), (Cells{"say \"hi\"", "x"}));
  EXPECT_EQ(split_csv_line("\"\",x"), (Cells{"", "x"}));
  EXPECT_EQ(split_csv_line("x,\"a \"\"b\"\", c\""), (Cells{"x", "a \"b\", c"}));
}

// csv_escape's cells read back as they were, whatever they hold.
TEST(CellText, SplitCsvLineInvertsCsvEscape) {
  const Cells cells = {"plain", "a,b", "say \"hi\"", "", ",", "\"\"", " lead", "x,\"y\",z"};
  std::string line;
  for (std::size_t i = 0; i < cells.size(); ++i) line += (i ? "," : "") + csv_escape(cells[i]);
  EXPECT_EQ(split_csv_line(line), cells);
}

// Python's csv.reader gives [] for an empty line; a CSV file's row of one empty cell is "" here,
// so that every line has at least one cell (callers skip blank lines themselves).
TEST(CellText, SplitCsvLineOfNothingIsOneEmptyCell) {
  EXPECT_EQ(split_csv_line(""), (Cells{""}));
}

TEST(CellText, SplitCsvLineRefusesBrokenQuotes) {
  EXPECT_THROW(split_csv_line("\"open,x"), std::invalid_argument);
  EXPECT_THROW(split_csv_line("\"a\"b,x"), std::invalid_argument);
  EXPECT_THROW(split_csv_line("a\"b,x"), std::invalid_argument);
}

// The table reader's rules: blanks around cells dropped, quoted or not; a line end ends a cell,
// and `pos` stays on it so that the reader can end the row.
TEST(CellText, ReadCsvCellUnderTheTableRules) {
  const CsvRules table{true, true};
  const std::string text = "  a b  , \"x,y\" ,c\r\nnext";
  std::size_t pos = 0;
  bool quoted = true;
  EXPECT_EQ(read_csv_cell(text, pos, table, &quoted), "a b");
  EXPECT_FALSE(quoted);
  EXPECT_EQ(text[pos], ',');
  ++pos;
  EXPECT_EQ(read_csv_cell(text, pos, table, &quoted), "x,y");
  EXPECT_TRUE(quoted);
  ++pos;
  EXPECT_EQ(read_csv_cell(text, pos, table), "c");
  EXPECT_EQ(text[pos], '\r');
  // The same text split as a line: blanks kept, CR and LF ordinary characters.
  EXPECT_THROW(split_csv_line(text), std::invalid_argument);  // " \"x,y\" " is not one cell
  EXPECT_EQ(split_csv_line("  a b  ,c\r"), (Cells{"  a b  ", "c\r"}));
}

// Where each broken cell is found: the opening quote of a cell never closed, the text after a
// closing quote, the stray quote (the table reader names the line from it).
TEST(CellText, ReadCsvCellSaysWhereTheCellIsBroken) {
  const auto error_at = [](const std::string& text) -> std::size_t {
    std::size_t pos = 0;
    try {
      read_csv_cell(text, pos, CsvRules{true, true});
    } catch (const CsvCellError& e) {
      return e.at;
    }
    return std::string::npos;
  };
  EXPECT_EQ(error_at("  \"open\nstill"), 2u);
  EXPECT_EQ(error_at("\"a\" b"), 4u);  // blanks after the closing quote are dropped first
  EXPECT_EQ(error_at("ab\"c"), 2u);
  EXPECT_EQ(error_at("fine"), std::string::npos);
}

}  // namespace
}  // namespace ra::util
