// The report's text pages: its blocks set on PDF pages (see pdf_writer.h).
#include "report/pdf_writer.h"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "report/pdf_tables.h"

namespace ra::report {
namespace {

constexpr double kHeadingSize[4] = {0, 24, 18, 15};  // points, by heading level

class Writer : public PdfTables {
 public:
  Writer(const Document& doc, const std::string& path, const PageNumbers& numbers)
      : PdfTables(path, doc.title, doc.footer, numbers.total), doc_(doc), numbers_(numbers) {}

  PdfLayoutResult run() {
    start_page();
    title_block();
    for (std::size_t i = 0; i < doc_.blocks.size(); ++i) {
      // a heading stays with the row of pictures under it (at the smallest size that row takes)
      const Block& b = doc_.blocks[i];
      if (b.kind == Block::Kind::kHeading && i + 1 < doc_.blocks.size() &&
          doc_.blocks[i + 1].kind == Block::Kind::kImage && !doc_.blocks[i + 1].row.empty())
        keep_with_next_ = plan_row(doc_.blocks[i + 1]).height * 2 / 3;
      block(b);
      keep_with_next_ = 0;
    }
    close();
    return {page_, heading_pages_};
  }

 private:
  const Document& doc_;
  const PageNumbers& numbers_;
  std::map<std::string, int> heading_pages_;
  double keep_with_next_ = 0;  // points of the next block a heading keeps on its page

  void title_block() {
    font(kSans, true, 28);
    color(0);
    for (const std::string& l : wrap(doc_.title, avail())) {
      y_ += 28 * 1.25;
      text(kMarginX, y_, l);
    }
    y_ += 8;
    font(kSans, false, 13);
    color(0.3);
    for (const std::string& s : doc_.subtitle)
      for (const std::string& l : wrap(s, avail())) {
        y_ += 13 * 1.45;
        text(kMarginX, y_, l);
      }
    color(0);
    y_ += 18;
    page_empty_ = false;
  }

  void block(const Block& b) {
    switch (b.kind) {
      case Block::Kind::kHeading: heading(b); break;
      case Block::Kind::kParagraph: {
        // a paragraph all in bold (a report's conclusion) is set in bold, a size larger
        const bool bold = b.text.size() > 4 && b.text.rfind("**", 0) == 0 &&
                          b.text.find("**", 2) == b.text.size() - 2;
        paragraph(b.text, bold ? kBody + 2 : kBody, 0, kSans, 0, bold);
        y_ += bold ? 12 : 7;
        break;
      }
      case Block::Kind::kBullets:
        for (const std::string& item : b.items) {
          font(kSans, false, kBody);
          const auto lines = wrap(plain_text(item), avail() - 22);
          need(kBody * kLine);
          for (std::size_t i = 0; i < lines.size(); ++i) {
            need(kBody * kLine);
            font(kSans, false, kBody);
            y_ += kBody * kLine;
            if (i == 0) text(kMarginX + 6, y_ - kBody * 0.3, "\u2022");
            text(kMarginX + 22, y_ - kBody * 0.3, lines[i]);
            page_empty_ = false;
          }
          y_ += 2;
        }
        y_ += 6;
        break;
      case Block::Kind::kPreformatted: {
        std::stringstream ss(b.text);
        std::string line;
        while (std::getline(ss, line)) {
          need(11.5 * 1.35);
          font(kMono, false, 11.5);
          for (const std::string& l : wrap(line.empty() ? " " : line, avail() - 24)) {
            need(11.5 * 1.35);
            font(kMono, false, 11.5);
            // a code block's grey ground, line by line (so that it follows a page break)
            cairo_set_source_rgb(cr_, 0.95, 0.95, 0.95);
            cairo_rectangle(cr_, kMarginX, y_, avail(), 11.5 * 1.35);
            cairo_fill(cr_);
            color(0);
            y_ += 11.5 * 1.35;
            text(kMarginX + 12, y_ - 3.5, l);
            page_empty_ = false;
          }
        }
        y_ += 10;
        break;
      }
      case Block::Kind::kTable: table(b.table); break;
      case Block::Kind::kFigureList: figure_list(); break;
      case Block::Kind::kContents: contents(); break;
      case Block::Kind::kPageBreak:
        if (!page_empty_) new_page();
        break;
      case Block::Kind::kImage: image(b); break;
      case Block::Kind::kNotes:
        for (const std::string& n : b.items) paragraph(n, 11.5, 0, kSans, 0.25);
        y_ += 7;
        break;
    }
  }

  // A PNG scaled to the text width (at most its share of the page's height), its caption under
  // it. A file that cannot be read is said in its place.
  void image(const Block& b) {
    if (!b.row.empty()) {
      image_row(b);
      return;
    }
    cairo_surface_t* png = cairo_image_surface_create_from_png(b.image_path.c_str());
    if (cairo_surface_status(png) != CAIRO_STATUS_SUCCESS) {
      cairo_surface_destroy(png);
      paragraph("(picture " + b.image_path + " could not be read)", kBody - 2, 0, kSans, 0.4);
      y_ += 7;
      return;
    }
    const double w = cairo_image_surface_get_width(png), h = cairo_image_surface_get_height(png);
    font(kSans, false, kBody - 3);
    const auto caption = wrap(plain_text(b.text), avail());
    const double caption_h = 8 + double(caption.size()) * (kBody - 3) * kLine;
    // As large as its share of the page allows, or smaller to stay on this page while it is
    // still readable (two thirds of that size): a picture is not what should start a new page.
    const double max_h = b.image_height_fraction * (bottom() - kMarginTop);
    const double room = bottom() - y_ - 4 - caption_h;
    const double fit = std::min(max_h, room) >= max_h * 2 / 3 ? std::min(max_h, room) : max_h;
    const double scale = std::min(avail() / w, fit / h);
    need(h * scale + caption_h);
    cairo_save(cr_);
    cairo_translate(cr_, kMarginX, y_ + 4);
    cairo_scale(cr_, scale, scale);
    cairo_set_source_surface(cr_, png, 0, 0);
    cairo_paint(cr_);
    cairo_restore(cr_);
    cairo_surface_destroy(png);
    y_ += h * scale + 8;
    page_empty_ = false;
    paragraph(b.text, kBody - 3, 0, kSans, 0.25);
    y_ += 7;
  }

  // How a row of pictures is set: side by side, each in an equal share of the text width at the
  // same scale (so that a before and an after compare pixel for pixel); or, for wide pictures (a
  // long line's strip) where that makes them half as large again or more, one under the other at
  // full width, kept on one page.
  struct RowPlan {
    bool stacked = false;
    double cell = 0, gap = 0, scale = 1, tallest = 0;
    double caption_h = 0;  // of the tallest caption of a line of pictures
    double height = 0;     // of all its lines of pictures, with their captions
  };
  RowPlan plan_row(const Block& b) {
    constexpr double kGap = 18;
    const std::size_t n = b.row.size();
    RowPlan plan;
    double widest = 0;
    for (const Picture& p : b.row) {
      cairo_surface_t* png = cairo_image_surface_create_from_png(p.path.c_str());
      if (cairo_surface_status(png) == CAIRO_STATUS_SUCCESS) {
        widest = std::max(widest, double(cairo_image_surface_get_width(png)));
        plan.tallest = std::max(plan.tallest, double(cairo_image_surface_get_height(png)));
      }
      cairo_surface_destroy(png);
    }
    const auto caption_h = [&](double cell) {
      font(kSans, false, kBody - 3);
      std::size_t lines = 1;
      for (const Picture& p : b.row) lines = std::max(lines, wrap(plain_text(p.caption), cell).size());
      return 12 + double(lines) * (kBody - 3) * kLine;
    };
    const double cell = (avail() - kGap * double(n - 1)) / double(n), side_caption = caption_h(cell);
    const double full_caption = caption_h(avail());
    const double frame = b.image_height_fraction * (bottom() - kMarginTop);
    if (plan.tallest <= 0) {  // nothing readable: the notes in a line
      plan.cell = cell, plan.gap = kGap, plan.caption_h = side_caption;
      plan.height = (kBody - 3) * kLine + side_caption;
      return plan;
    }
    const double side = std::min(cell / widest, frame / plan.tallest);
    const double stacked = std::min(avail() / widest, (bottom() - kMarginTop - 8 -
                                                       double(n) * full_caption) /
                                                          (double(n) * plan.tallest));
    plan.stacked = stacked > 1.5 * side;
    plan.cell = plan.stacked ? avail() : cell;
    plan.gap = plan.stacked ? 0 : kGap;
    plan.scale = plan.stacked ? stacked : side;
    plan.caption_h = plan.stacked ? full_caption : side_caption;
    plan.height = (plan.stacked ? double(n) : 1) * (plan.tallest * plan.scale + plan.caption_h);
    return plan;
  }

  // A row of pictures (see plan_row), smaller to stay on this page while still two thirds of its
  // size, then the block's own caption under all.
  void image_row(const Block& b) {
    RowPlan plan = plan_row(b);
    const double room = bottom() - y_;
    if (plan.tallest > 0 && plan.height > room && room >= plan.height * 2 / 3) {
      const double lines = plan.stacked ? double(b.row.size()) : 1;
      plan.scale = std::max(0.0, (room - lines * plan.caption_h) / (lines * plan.tallest));
      plan.height = room;
    }
    need(plan.height);
    std::vector<cairo_surface_t*> pngs;
    for (const Picture& p : b.row) {
      cairo_surface_t* png = cairo_image_surface_create_from_png(p.path.c_str());
      if (cairo_surface_status(png) != CAIRO_STATUS_SUCCESS) {
        cairo_surface_destroy(png);
        png = nullptr;
      }
      pngs.push_back(png);
    }
    if (plan.stacked) {
      for (std::size_t i = 0; i < b.row.size(); ++i) picture_line(b, pngs, {i}, plan);
    } else {
      std::vector<std::size_t> all;
      for (std::size_t i = 0; i < b.row.size(); ++i) all.push_back(i);
      picture_line(b, pngs, all, plan);
    }
    for (cairo_surface_t* png : pngs)
      if (png) cairo_surface_destroy(png);
    if (!b.text.empty()) paragraph(b.text, kBody - 3, 0, kSans, 0.25);
    y_ += 7;
  }

  // The pictures `which` of a row in one line, as planned, their captions under them.
  void picture_line(const Block& b, const std::vector<cairo_surface_t*>& pngs,
                    const std::vector<std::size_t>& which, const RowPlan& plan) {
    const double small = kBody - 3;
    const double picture_h = plan.tallest > 0 ? plan.tallest * plan.scale : small * kLine;
    for (std::size_t k = 0; k < which.size(); ++k) {
      const std::size_t i = which[k];
      const double x = kMarginX + double(k) * (plan.cell + plan.gap);
      if (pngs[i]) {
        cairo_save(cr_);
        cairo_translate(cr_, x, y_ + 4);
        cairo_scale(cr_, plan.scale, plan.scale);
        cairo_set_source_surface(cr_, pngs[i], 0, 0);
        cairo_paint(cr_);
        cairo_restore(cr_);
      } else {
        font(kSans, false, small);
        color(0.4);
        text(x, y_ + 4 + small, "(picture " + b.row[i].path + " could not be read)");
      }
      font(kSans, false, small);
      color(0.25);
      double ty = y_ + 8 + picture_h;
      for (const std::string& l : wrap(plain_text(b.row[i].caption), plan.cell)) {
        ty += small * kLine;
        text(x, ty - small * 0.3, l);
      }
      color(0);
    }
    y_ += picture_h + plan.caption_h;
    page_empty_ = false;
  }

  void heading(const Block& b) {
    const int level = std::clamp(b.level, 1, 3);
    const double size = kHeadingSize[level];
    // A section starts a page only where less than this share of the page is left: short
    // sections (no failures, a short experiment file) share a page instead of leaving it blank.
    constexpr double kSectionPageShare = 0.45;
    if (level == 1 && !page_empty_ && page_ > 0 &&
        bottom() - y_ < kSectionPageShare * (bottom() - kMarginTop))
      new_page();
    font(kSans, true, size);
    const auto lines = wrap(plain_text(b.text), avail());
    const double h = (level == 1 ? 4 : 14) + double(lines.size()) * size * 1.3 +
                     std::max(4 * kBody * kLine, keep_with_next_);
    need(h);
    if (!page_empty_) y_ += level == 1 ? 6 : 14;
    if (level == 1 && !b.anchor.empty()) heading_pages_[b.anchor] = page_;
    font(kSans, true, size);
    color(0);
    for (const std::string& l : lines) {
      y_ += size * 1.3;
      text(kMarginX, y_ - size * 0.25, l);
    }
    if (level == 1) {
      cairo_set_line_width(cr_, 1.2);
      cairo_move_to(cr_, kMarginX, y_ + 5);
      cairo_line_to(cr_, kPageWidth - kMarginX, y_ + 5);
      cairo_stroke(cr_);
      y_ += 10;
    }
    y_ += 6;
    page_empty_ = false;
  }

  std::string page_text(int page) { return page > 0 ? std::to_string(page) : "?"; }

  void figure_list() {
    Table t;
    t.title = "List of figures (one page each, after the text)";
    t.header = {"Figure", "Section", "Title", "Page"};
    t.right = {true, false, false, true};
    for (const FigureRef& f : doc_.figures)
      t.rows.push_back({std::to_string(f.number), f.section, f.title,
                        page_text(numbers_.first_figure_page
                                      ? numbers_.first_figure_page + f.number - 1
                                      : 0)});
    if (t.rows.empty()) {
      paragraph("No figure was drawn.");
      return;
    }
    table(t);
  }

  void contents() {
    Table t;
    t.title = "Contents";
    t.header = {"Section", "Page"};
    t.right = {false, true};
    for (const Block& b : doc_.blocks)
      if (b.kind == Block::Kind::kHeading && b.level == 1 && !b.anchor.empty()) {
        const auto it = numbers_.heading_pages.find(b.anchor);
        t.rows.push_back({plain_text(b.text), page_text(it == numbers_.heading_pages.end() ? 0 : it->second)});
      }
    if (!doc_.figures.empty())
      t.rows.push_back({"Figure pages (" + std::to_string(doc_.figures.size()) + ")",
                        page_text(numbers_.first_figure_page)});
    table(t);
  }
};

}  // namespace

PdfLayoutResult write_text_pdf(const Document& doc, const std::string& path,
                               const PageNumbers& numbers) {
  Writer w(doc, path, numbers);
  return w.run();
}

}  // namespace ra::report
