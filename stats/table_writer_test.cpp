// Tests of the table writer: one small table rendered to CSV, Markdown and LaTeX and compared line
// by line (an unintended format change fails here), escaping, number formatting without NaN.
#include "stats/table_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "analysis/records_testing.h"

namespace ra::stats {
namespace {

using analysis::testing::lines_of;

Table small_table() {
  Table t;
  t.file_stem = "table03_pe";
  t.title = "Table 3: PE, px, values x10^3; quartiles HF6";
  t.latex_title = "Table 3: PE, px, values $\\times 10^{3}$; quartiles HF6";
  t.notes = {"Sample: true-visible points.", "50% of a_b | c"};
  t.groups = {{"", 2}, {"osmesa_llvmpipe", 2}};
  t.columns = {{"View", Align::kLeft},
               {"FOV", Align::kRight},
               {"Median", Align::kRight},
               {"IQR", Align::kRight}};
  t.rows = {{text_cell("A"), text_cell("30"), number_cell(0.3, 5), number_cell(0.325, 5)},
            {text_cell("B"), text_cell("150"), text_cell("no data"), text_cell("no, data")}};
  t.rules_before = {0, 1};
  return t;
}

TEST(TableWriter, CsvLineByLine) {
  const std::vector<std::string> expected = {
      "# Table 3: PE, px, values x10^3; quartiles HF6",
      "# Sample: true-visible points.",
      "# 50% of a_b | c",
      "View,FOV,osmesa_llvmpipe Median,osmesa_llvmpipe IQR",
      "A,30,0.3,0.325",
      "B,150,no data,\"no, data\"",
  };
  EXPECT_EQ(lines_of(render_csv(small_table())), expected);
}

TEST(TableWriter, MarkdownLineByLine) {
  const std::vector<std::string> expected = {
      "### Table 3: PE, px, values x10^3; quartiles HF6",
      "",
      "| View | FOV | osmesa_llvmpipe Median | osmesa_llvmpipe IQR |",
      "| :--- | ---: | ---: | ---: |",
      "| A | 30 | 0.30000 | 0.32500 |",
      "| B | 150 | no data | no, data |",
      "",
      "- Sample: true-visible points.",
      "- 50% of a_b | c",
  };
  EXPECT_EQ(lines_of(render_markdown(small_table())), expected);
}

TEST(TableWriter, LatexLineByLine) {
  const std::vector<std::string> expected = {
      "% Table 3: PE, px, values x10^3; quartiles HF6",
      "% Written by renderaudit analyze; needs \\usepackage{booktabs}.",
      "\\begin{table}[htbp]",
      "\\centering",
      "\\caption{Table 3: PE, px, values $\\times 10^{3}$; quartiles HF6}",
      "\\label{tab:table03_pe}",
      "\\begin{tabular}{lrrr}",
      "\\toprule",
      "\\multicolumn{2}{c}{} & \\multicolumn{2}{c}{osmesa\\_llvmpipe} \\\\",
      "\\cmidrule(lr){3-4}",
      "View & FOV & Median & IQR \\\\",
      "\\midrule",
      "A & 30 & 0.30000 & 0.32500 \\\\",
      "\\midrule",
      "B & 150 & no data & no, data \\\\",
      "\\bottomrule",
      "\\end{tabular}",
      "",
      "\\smallskip",
      "{\\footnotesize",
      "Sample: true-visible points.\\par",
      "50\\% of a\\_b | c\\par",
      "}",
      "\\end{table}",
  };
  EXPECT_EQ(lines_of(render_latex(small_table())), expected);
}

TEST(TableWriter, MarkdownEscapesPipesInCells) {
  Table t;
  t.title = "t";
  t.columns = {{"a|b", Align::kLeft}};
  t.rows = {{text_cell("x|y")}};
  const std::string md = render_markdown(t);
  EXPECT_NE(md.find("| a\\|b |"), std::string::npos) << md;
  EXPECT_NE(md.find("| x\\|y |"), std::string::npos) << md;
}

TEST(TableWriter, LatexEscapesSpecialCharacters) {
  EXPECT_EQ(latex_escape("a_b & c% $d #e {f} ~g ^h \\i"),
            "a\\_b \\& c\\% \\$d \\#e \\{f\\} \\textasciitilde{}g \\textasciicircum{}h "
            "\\textbackslash{}i");
}

TEST(TableWriter, LatexTypesetsTheScaleOfTitlesAndNotes) {
  Table t;
  t.file_stem = "t";
  t.title = "PEnorm, values x10^3";
  t.notes = {"shown x10^6 (1.000 means 1e-6)"};
  t.columns = {{"a", Align::kLeft}};
  const std::string tex = render_latex(t);
  EXPECT_NE(tex.find("\\caption{PEnorm, values $\\times 10^{3}$}"), std::string::npos) << tex;
  EXPECT_NE(tex.find("shown $\\times 10^{6}$ (1.000 means 1e-6)\\par"), std::string::npos) << tex;
}

TEST(TableWriter, NumbersNeverShowANegativeZeroOrNaN) {
  EXPECT_EQ(format_fixed(-0.0001, 2), "0.00");
  EXPECT_EQ(format_fixed(-0.005, 2), "-0.01");
  EXPECT_EQ(format_fixed(-0.0, 3), "0.000");
  EXPECT_EQ(format_significant(-0.0, 3), "0");
  EXPECT_EQ(number_cell(1.0 / 3, 3).text, "0.333");
  EXPECT_EQ(number_cell(1.0 / 3, 3).csv, "0.333333333");
  EXPECT_THROW(number_cell(std::nan(""), 2), std::logic_error);
  EXPECT_THROW(significant_cell(std::numeric_limits<double>::infinity()), std::logic_error);
}

TEST(TableWriter, InconsistentTablesAreRejected) {
  Table t = small_table();
  t.rows[1].pop_back();
  EXPECT_THROW(render_csv(t), std::logic_error);
  t = small_table();
  t.groups[1].span = 3;
  EXPECT_THROW(render_markdown(t), std::logic_error);
}

// The row-at-a-time pieces spell a table as render_markdown does, and every alignment as Markdown
// writes it.
TEST(TableWriter, MarkdownHeaderAndRows) {
  EXPECT_EQ(markdown_header({"a", "b", "c", "d"},
                            {Align::kLeft, Align::kRight, Align::kCenter, Align::kDefault}),
            "| a | b | c | d |\n| :--- | ---: | :---: | --- |\n");
  EXPECT_EQ(markdown_header({"Scene", "Method", "Mean"}, 2),
            "| Scene | Method | Mean |\n| --- | --- | ---: |\n");
  EXPECT_EQ(markdown_row({"x|y", "two\nlines", ""}), "| x\\|y | two lines |  |\n");
  EXPECT_THROW(markdown_header({"a", "b"}, {Align::kLeft}), std::logic_error);
  EXPECT_EQ(markdown_rule({Align::kLeft, Align::kRight}), "| :--- | ---: |\n");
  EXPECT_EQ(markdown_compact_rule(3), "|---|---|---|\n");
}

}  // namespace
}  // namespace ra::stats
