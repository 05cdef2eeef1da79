// Tables on PDF pages: a table repeats its title ("continued") and header row across pages, wraps
// long cells within their column, shrinks its font to fit the text width and, when even that is
// too wide, is split into column groups that repeat the leading key columns.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "report/document.h"
#include "report/pdf_pages.h"

namespace ra::report {

class PdfTables : public PdfPages {
 public:
  using PdfPages::PdfPages;

 protected:
  // `t` from the cursor down, its notes under it.
  void table(const Table& t);

 private:
  struct Fit;
  // Width of the widest word of `s` in the current font.
  double longest_word(const std::string& s);
  // Column widths at a font size: each column at least as wide as its widest cell and its
  // header's longest word; the space left over goes to headers that would otherwise wrap,
  // narrowest need first, so that as many as possible stay on one line.
  Fit fit_columns(const Table& t, const std::vector<std::size_t>& cols, double size);
  // The columns `cols` of `t` (one column group, `suffix` added to its title).
  void table_part(const Table& t, const std::vector<std::size_t>& cols, const Fit& f,
                  const std::string& suffix);
};

}  // namespace ra::report
