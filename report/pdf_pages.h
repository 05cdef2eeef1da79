// Pages of text on cairo's PDF surface: the cursor down the page, fonts, word wrapping,
// paragraphs and the footer. Lengths in points, y from the top of the page. The report's tables
// (pdf_tables.h) and its document blocks (pdf_writer.cpp) are set on it.
#pragma once

#include <cairo.h>

#include <string>
#include <vector>

#include "report/pdf_writer.h"

namespace ra::report {

class PdfPages {
 public:
  // Opens `path` for writing (empty: lay out only, nothing written); pages are footed with
  // `footer` and "page N of `total_pages`" (0: "page N"). Throws ra::util::UserError when cairo
  // cannot create the file.
  PdfPages(const std::string& path, const std::string& title, const std::string& footer,
           int total_pages);
  ~PdfPages();
  PdfPages(const PdfPages&) = delete;
  PdfPages& operator=(const PdfPages&) = delete;

 protected:
  static constexpr const char* kSans = "DejaVu Sans";
  static constexpr const char* kMono = "DejaVu Sans Mono";
  static constexpr double kMarginX = 60, kMarginTop = 54, kMarginBottom = 58;
  static constexpr double kBody = 14, kLine = 1.42;  // body text size, line height over size

  // Finishes the last page and the file; throws ra::util::UserError when cairo could not write it.
  void close();

  double avail() const { return kPageWidth - 2 * kMarginX; }
  double bottom() const { return kPageHeight - kMarginBottom; }

  void font(const char* family, bool bold, double size);
  double width(const std::string& s);  // advance of `s` in the current font
  void color(double grey) { cairo_set_source_rgb(cr_, grey, grey, grey); }
  void text(double x, double baseline, const std::string& s);
  // Lines of at most `max` points, broken at spaces (a word longer than a line is cut).
  std::vector<std::string> wrap(const std::string& s, double max);
  // Markdown-marked text `s` as wrapped lines from the cursor down, breaking pages as needed.
  void paragraph(const std::string& s, double size = kBody, double indent = 0,
                 const char* family = kSans, double grey = 0, bool bold = false);

  void start_page();
  void finish_page();
  void new_page();
  // Ensures `h` points of space, starting a page when needed.
  void need(double h);

  cairo_t* cr_ = nullptr;
  int page_ = 0;
  double y_ = 0;  // top of the free space, points from the top
  bool page_empty_ = true;

 private:
  std::string path_;
  std::string footer_;
  int total_pages_ = 0;
  cairo_surface_t* surface_ = nullptr;
};

}  // namespace ra::report
