// The report's Markdown reader and its PDF pages: what goes in comes out, as text pdftotext finds.
#include "report/document.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "report/html_writer.h"
#include "report/pdf_writer.h"
#include "tests/cli_harness.h"

namespace ra::report {
namespace {

using ra::testing_cli::shell_output;
using ra::testing_cli::squeeze;



// Why: the analysis stage's tables come as Markdown ("### title", pipe table, "- " notes); the
// report must keep the title with its table, the alignment and the notes.
TEST(ReportMarkdown, ReadsTitledTablesWithNotes) {
  const std::string md =
      "# View equivalence\n\nSome *text* here,\ncontinued.\n\n## Verdicts\n\n- one\n- two\n\n"
      "### Table 3: PE | px\n\n| View | FOV | a\\|b |\n| :--- | ---: | ---: |\n| A | 30 | 0.39 |\n"
      "| B | 150 | 0.40 |\n\n- Units: pixels.\n- Sample: true-visible.\n";
  const auto blocks = parse_markdown(md, 1);
  ASSERT_EQ(blocks.size(), 5u);
  EXPECT_EQ(blocks[0].kind, Block::Kind::kHeading);
  EXPECT_EQ(blocks[0].level, 2);
  EXPECT_EQ(blocks[1].kind, Block::Kind::kParagraph);
  EXPECT_EQ(blocks[1].text, "Some *text* here, continued.");
  EXPECT_EQ(blocks[2].level, 3);
  EXPECT_EQ(blocks[3].kind, Block::Kind::kBullets);
  EXPECT_EQ(blocks[3].items, (std::vector<std::string>{"one", "two"}));
  const Table& t = blocks[4].table;
  EXPECT_EQ(blocks[4].kind, Block::Kind::kTable);
  EXPECT_EQ(t.title, "Table 3: PE | px");
  EXPECT_EQ(t.header, (std::vector<std::string>{"View", "FOV", "a|b"}));
  EXPECT_EQ(t.right, (std::vector<bool>{false, true, true}));
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[1], (std::vector<std::string>{"B", "150", "0.40"}));
  EXPECT_EQ(t.notes, (std::vector<std::string>{"Units: pixels.", "Sample: true-visible."}));
}

// Why: tables wider than a page are split into column groups that repeat the key column, and
// tables longer than a page continue with their header: every cell must still be in the PDF, and
// the pages counted by the writer must be the pages in the file.
TEST(ReportPdf, WideAndLongTablesKeepEveryCell) {
  Document doc;
  doc.title = "Test document";
  doc.footer = "footer text";
  Block h;
  h.kind = Block::Kind::kHeading;
  h.text = "1. Wide";
  h.anchor = "wide";
  doc.blocks.push_back(h);
  Block wide;
  wide.kind = Block::Kind::kTable;
  wide.table.title = "A wide table";
  wide.table.header.push_back("key");
  wide.table.right.push_back(false);
  for (int c = 0; c < 40; ++c) {
    wide.table.header.push_back("column number " + std::to_string(c));
    wide.table.right.push_back(true);
  }
  for (int r = 0; r < 3; ++r) {
    std::vector<std::string> row = {"row" + std::to_string(r)};
    for (int c = 0; c < 40; ++c) row.push_back("v" + std::to_string(r) + "x" + std::to_string(c) + "yyyyyy");
    wide.table.rows.push_back(row);
  }
  doc.blocks.push_back(wide);
  Block tall;
  tall.kind = Block::Kind::kTable;
  tall.table.title = "A long table";
  tall.table.header = {"n", "square"};
  tall.table.right = {true, true};
  for (int r = 0; r < 120; ++r) tall.table.rows.push_back({std::to_string(r), std::to_string(r * r) + "sq"});
  doc.blocks.push_back(tall);

  const auto dir = std::filesystem::temp_directory_path() / "renderaudit_report_pdf_test";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "doc.pdf").string();
  const PdfLayoutResult r = write_text_pdf(doc, path, {});
  EXPECT_GE(r.pages, 3);
  const std::string info = shell_output("pdfinfo '" + path + "'");
  EXPECT_NE(info.find("Pages:           " + std::to_string(r.pages) + "\n"), std::string::npos) << info;
  const std::string text = squeeze(shell_output("pdftotext '" + path + "' -"));
  for (int r2 = 0; r2 < 3; ++r2)
    for (int c = 0; c < 40; ++c) {
      const std::string cell = "v" + std::to_string(r2) + "x" + std::to_string(c) + "yyyyyy";
      EXPECT_NE(text.find(cell), std::string::npos) << cell;
    }
  EXPECT_NE(text.find("A wide table (part 2 of"), std::string::npos);
  EXPECT_NE(text.find("A long table (continued)"), std::string::npos);
  for (int n : {0, 57, 119}) EXPECT_NE(text.find(std::to_string(n * n) + "sq"), std::string::npos) << n;
  // page 1 holds the title block and more than half a page is left: the section starts there
  EXPECT_EQ(r.heading_pages.at("wide"), 1);

  // The same blocks in HTML: one <table> per table, the cells escaped.
  const std::string html = render_html(doc);
  EXPECT_NE(html.find("<caption>A wide table</caption>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"num\">14161sq</td>"), std::string::npos);
}


// Sections share a page while at least 45% of it is left, and start a new one below that: a
// section of three lines does not leave a page blank, a section near the bottom is not cut.
TEST(ReportPdf, ShortSectionsShareAPageAndLateOnesStartANewOne) {
  Document doc;
  doc.title = "Sections";
  const auto section = [&](const std::string& anchor, int lines) {
    Block h;
    h.kind = Block::Kind::kHeading;
    h.text = anchor;
    h.anchor = anchor;
    doc.blocks.push_back(h);
    for (int i = 0; i < lines; ++i) {
      Block p;
      p.text = "line " + std::to_string(i) + " of section " + anchor;
      doc.blocks.push_back(p);
    }
  };
  section("short", 3);   // page 1, under the title
  section("next", 3);    // page 1 too: most of the page is left
  section("long", 8);    // page 1 still, ending past its middle
  section("late", 2);    // less than 45% of page 1 left: page 2
  const PdfLayoutResult r = write_text_pdf(doc, "", {});
  EXPECT_EQ(r.heading_pages.at("short"), 1);
  EXPECT_EQ(r.heading_pages.at("next"), 1);
  EXPECT_EQ(r.heading_pages.at("long"), 1);
  EXPECT_EQ(r.heading_pages.at("late"), 2);
}

}  // namespace
}  // namespace ra::report
