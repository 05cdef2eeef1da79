// Pages of text on cairo's PDF surface (see pdf_pages.h).
#include "report/pdf_pages.h"

#include <cairo-pdf.h>

#include <sstream>

#include "report/document.h"
#include "util/errors.h"

namespace ra::report {
namespace {

cairo_status_t discard(void*, const unsigned char*, unsigned int) { return CAIRO_STATUS_SUCCESS; }

}  // namespace

PdfPages::PdfPages(const std::string& path, const std::string& title, const std::string& footer,
                   int total_pages)
    : path_(path), footer_(footer), total_pages_(total_pages) {
  surface_ = path.empty()
                 ? cairo_pdf_surface_create_for_stream(discard, nullptr, kPageWidth, kPageHeight)
                 : cairo_pdf_surface_create(path.c_str(), kPageWidth, kPageHeight);
  if (cairo_surface_status(surface_) != CAIRO_STATUS_SUCCESS)
    throw util::UserError("cannot create " + path + ": " +
                          cairo_status_to_string(cairo_surface_status(surface_)));
  cairo_pdf_surface_set_metadata(surface_, CAIRO_PDF_METADATA_TITLE, title.c_str());
  cairo_pdf_surface_set_metadata(surface_, CAIRO_PDF_METADATA_CREATOR, "renderaudit report");
  cr_ = cairo_create(surface_);
}

PdfPages::~PdfPages() {
  if (cr_) cairo_destroy(cr_);
  if (surface_) cairo_surface_destroy(surface_);
}

void PdfPages::close() {
  finish_page();
  cairo_surface_finish(surface_);
  if (cairo_surface_status(surface_) != CAIRO_STATUS_SUCCESS)
    throw util::UserError("cannot write " + path_ + ": " +
                          cairo_status_to_string(cairo_surface_status(surface_)));
}

void PdfPages::font(const char* family, bool bold, double size) {
  cairo_select_font_face(cr_, family, CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr_, size);
}

double PdfPages::width(const std::string& s) {
  cairo_text_extents_t e;
  cairo_text_extents(cr_, s.c_str(), &e);
  return e.x_advance;
}

void PdfPages::text(double x, double baseline, const std::string& s) {
  cairo_move_to(cr_, x, baseline);
  cairo_show_text(cr_, s.c_str());
}

std::vector<std::string> PdfPages::wrap(const std::string& s, double max) {
  std::vector<std::string> out;
  std::string word, cur;
  const auto cut_overlong_word = [&] {
    while (width(cur) > max && cur.size() > 1) {
      std::size_t n = cur.size();
      while (n > 1 && width(cur.substr(0, n)) > max) --n;
      out.push_back(cur.substr(0, n));
      cur = cur.substr(n);
    }
  };
  std::stringstream ss(s);
  while (ss >> word) {
    const std::string cand = cur.empty() ? word : cur + " " + word;
    if (width(cand) <= max || cur.empty()) {
      cur = cand;
    } else {
      out.push_back(cur);
      cur = word;
    }
    cut_overlong_word();
  }
  if (!cur.empty()) out.push_back(cur);
  if (out.empty()) out.push_back("");
  return out;
}

void PdfPages::paragraph(const std::string& s, double size, double indent, const char* family,
                         double grey, bool bold) {
  font(family, bold, size);
  const auto lines = wrap(plain_text(s), avail() - indent);
  for (const std::string& l : lines) {
    need(size * kLine);
    font(family, bold, size);
    color(grey);
    y_ += size * kLine;
    text(kMarginX + indent, y_ - size * 0.3, l);
    page_empty_ = false;
  }
  color(0);
}
void PdfPages::start_page() {
  ++page_;
  y_ = kMarginTop;
  page_empty_ = true;
}

void PdfPages::finish_page() {
  font(kSans, false, 10.5);
  color(0.4);
  text(kMarginX, kPageHeight - 28, footer_);
  const std::string right =
      "page " + std::to_string(page_) + (total_pages_ ? " of " + std::to_string(total_pages_) : "");
  text(kPageWidth - kMarginX - width(right), kPageHeight - 28, right);
  cairo_set_line_width(cr_, 0.6);
  cairo_move_to(cr_, kMarginX, kPageHeight - 44);
  cairo_line_to(cr_, kPageWidth - kMarginX, kPageHeight - 44);
  cairo_stroke(cr_);
  color(0);
  cairo_show_page(cr_);
}

void PdfPages::new_page() {
  finish_page();
  start_page();
}

void PdfPages::need(double h) {
  if (y_ + h > bottom() && !page_empty_) new_page();
}

}  // namespace ra::report
