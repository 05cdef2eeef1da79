// Tests of stats/csv_table.h: quoting, missing cells, and located errors.
#include "stats/csv_table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "stats/stats_testing.h"
#include "util/errors.h"
#include "tests/cli_harness.h"

namespace ra::stats {
namespace {

// The message of the UserError that `f` throws ("" when it throws none).
template <typename F>
std::string user_error(F f) {
  return ra::testing_cli::error_message<util::UserError>(f);
}

TEST(CsvTable, QuotedCellsAndMissingValues) {
  const CsvTable t = CsvTable::parse(
      "\xEF\xBB\xBFname, value ,\"note, with comma\"\r\n"
      "a, 1.5 ,\"say \"\"hi\"\"\"\r\n"
      "\n"
      "\"b\",,\"two\nlines\"\n"
      "c,-2e-3,\n",
      "mem.csv");
  EXPECT_EQ(t.header(), (std::vector<std::string>{"name", "value", "note, with comma"}));
  ASSERT_EQ(t.row_count(), 3u);
  EXPECT_EQ(t.cell(0, 2), "say \"hi\"");
  EXPECT_EQ(t.cell(1, 0), "b");
  EXPECT_EQ(t.cell(1, 2), "two\nlines");
  EXPECT_EQ(t.line(0), 2u);
  EXPECT_EQ(t.line(1), 4u);  // the blank line 3 is skipped
  EXPECT_EQ(t.line(2), 6u);  // the quoted line break counts
  const NumericColumn v = t.numeric_column("value");
  EXPECT_EQ(v.values, (std::vector<double>{1.5, -2e-3}));
  EXPECT_EQ(v.rows, (std::vector<std::size_t>{0, 2}));
  EXPECT_EQ(v.n_missing, 1u);
}

TEST(CsvTable, ParseNumber) {
  EXPECT_EQ(parse_number("42"), 42.0);
  EXPECT_EQ(parse_number("+1.5e3"), 1500.0);
  EXPECT_EQ(parse_number("-.25"), -0.25);
  EXPECT_FALSE(parse_number(""));
  EXPECT_FALSE(parse_number("1.5x"));
  EXPECT_FALSE(parse_number("nan"));
  EXPECT_FALSE(parse_number("inf"));
  EXPECT_FALSE(parse_number("1e999"));  // out of range
  EXPECT_FALSE(parse_number("+-1"));
  EXPECT_FALSE(parse_number("0x10"));
}

TEST(CsvTable, ErrorsAreLocated) {
  EXPECT_NE(user_error([] { CsvTable::parse("a,b\n1,2\n3\n", "f.csv"); }).find("f.csv:3: 1 cells"),
            std::string::npos);
  EXPECT_NE(user_error([] { CsvTable::parse("a,a\n", "f.csv"); }).find("f.csv:1: column name 'a'"),
            std::string::npos);
  EXPECT_NE(user_error([] { CsvTable::parse("a\n\"open\n", "f.csv"); }).find("f.csv:2: a quoted"),
            std::string::npos);
  EXPECT_NE(user_error([] { CsvTable::parse("", "f.csv"); }).find("empty file"), std::string::npos);
  const CsvTable t = CsvTable::parse("x,y\n1,2\n3,abc\n", "g.csv");
  const std::string unknown = user_error([&] { t.column("z"); });
  EXPECT_NE(unknown.find("no column named 'z'"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("available: x, y"), std::string::npos) << unknown;
  const std::string bad = user_error([&] { t.numeric_column("y"); });
  EXPECT_NE(bad.find("g.csv:3: column 'y': 'abc' is not a finite number"), std::string::npos)
      << bad;
  EXPECT_NE(
      user_error([] { CsvTable::read_file("/nonexistent/x.csv"); }).find("/nonexistent/x.csv"),
      std::string::npos);
}

// A records file ends with its seal line ("# complete rows=N fnv1a64=H"); `stats describe` on it
// failed with "1 cells, but the header has 37 columns" before comment lines were skipped.
TEST(CsvTable, CommentLinesAreSkippedAndLaterLinesKeepTheirNumbers) {
  const CsvTable t =
      CsvTable::parse("# provenance\nplatform,pe\na,0.5\nb,\n# complete rows=2 fnv1a64=99\n", "r.csv");
  EXPECT_EQ(t.header(), (std::vector<std::string>{"platform", "pe"}));
  const NumericColumn pe = t.numeric_column("pe");
  EXPECT_EQ(pe.values, (std::vector<double>{0.5}));
  EXPECT_EQ(pe.n_missing, 1u);
  EXPECT_NE(user_error([] { CsvTable::parse("a,b\n# note\n1\n", "f.csv"); }).find("f.csv:3: 1 cells"),
            std::string::npos);
  // a '#' that is not the first character of a line is an ordinary cell
  const CsvTable hash = CsvTable::parse("a,b\nx,#1\n", "f.csv");
  EXPECT_EQ(hash.cell(0, hash.column("b")), "#1");
}

TEST(CsvTable, ReadsFiles) {
  const auto dir = stats::testing::temp_dir("csv");
  const auto path = (dir / "t.csv").string();
  std::ofstream(path) << "v\n1\n2\n";
  const CsvTable t = CsvTable::read_file(path);
  EXPECT_EQ(t.source(), path);
  EXPECT_EQ(t.numeric_column("v").values, (std::vector<double>{1, 2}));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace ra::stats
