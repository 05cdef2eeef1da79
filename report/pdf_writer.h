// The text and table pages of the report as PDF, drawn with cairo's PDF surface (libcairo2, with
// DejaVu Sans embedded as a subset: every text is real text that pdftotext and search find).
//
// Page size: 1123 x 794 pt, the size of the figure pages VTK exports (1123 x 794 px windows), so
// the assembled report has one page size; it is A4 landscape scaled by 4/3, and printed on A4 the
// 14 pt body text comes out at 10.5 pt and table text (11.5 pt, 9 pt at least) at 8.6 pt (6.8 pt).
//
// Layout: level-1 headings start a page; a heading is kept with what follows; tables repeat
// their title ("continued") and header row across pages, wrap long cells within their column,
// shrink their font to fit the width and, when even that is too wide, are split into column
// groups that repeat the leading key columns.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "report/document.h"

namespace ra::report {

constexpr double kPageWidth = 1123;  // points
constexpr double kPageHeight = 794;

// Page numbers the text refers to, known after a first layout pass.
struct PageNumbers {
  int total = 0;              // pages of the whole report (0: not known yet)
  int first_figure_page = 0;  // page of figure 1 (0: not known yet)
  std::map<std::string, int> heading_pages;  // anchor of a level-1 heading -> its page
};

struct PdfLayoutResult {
  int pages = 0;  // text pages written
  std::map<std::string, int> heading_pages;
};

// Writes the text pages of `doc` (everything but the figures) to `path` (empty: lay out only,
// nothing written). Throws ra::util::UserError when cairo cannot write the file.
PdfLayoutResult write_text_pdf(const Document& doc, const std::string& path,
                               const PageNumbers& numbers);

}  // namespace ra::report
