// Text and table pages with cairo (see pdf_writer.h).
#include "report/pdf_writer.h"

#include <cairo-pdf.h>
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "util/errors.h"

namespace ra::report {
namespace {

constexpr const char* kSans = "DejaVu Sans";
constexpr const char* kMono = "DejaVu Sans Mono";
constexpr double kMarginX = 60, kMarginTop = 54, kMarginBottom = 58;
constexpr double kBody = 14, kLine = 1.42;
constexpr double kTableFont = 11.5, kTableFontMin = 9, kPad = 5;
constexpr double kHeadingSize[4] = {0, 24, 18, 15};

cairo_status_t discard(void*, const unsigned char*, unsigned int) { return CAIRO_STATUS_SUCCESS; }

class Writer {
 public:
  Writer(const Document& doc, const std::string& path, const PageNumbers& numbers)
      : doc_(doc), numbers_(numbers) {
    surface_ = path.empty()
                   ? cairo_pdf_surface_create_for_stream(discard, nullptr, kPageWidth, kPageHeight)
                   : cairo_pdf_surface_create(path.c_str(), kPageWidth, kPageHeight);
    if (cairo_surface_status(surface_) != CAIRO_STATUS_SUCCESS)
      throw util::UserError("cannot create " + path + ": " +
                            cairo_status_to_string(cairo_surface_status(surface_)));
    cairo_pdf_surface_set_metadata(surface_, CAIRO_PDF_METADATA_TITLE, doc.title.c_str());
    cairo_pdf_surface_set_metadata(surface_, CAIRO_PDF_METADATA_CREATOR, "renderaudit report");
    cr_ = cairo_create(surface_);
    path_ = path;
  }
  ~Writer() {
    if (cr_) cairo_destroy(cr_);
    if (surface_) cairo_surface_destroy(surface_);
  }

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
    finish_page();
    cairo_surface_finish(surface_);
    if (cairo_surface_status(surface_) != CAIRO_STATUS_SUCCESS)
      throw util::UserError("cannot write " + path_ + ": " +
                            cairo_status_to_string(cairo_surface_status(surface_)));
    return {page_, heading_pages_};
  }

 private:
  const Document& doc_;
  const PageNumbers& numbers_;
  std::string path_;
  cairo_surface_t* surface_ = nullptr;
  cairo_t* cr_ = nullptr;
  int page_ = 0;
  double y_ = 0;  // top of the free space, points from the top
  bool page_empty_ = true;
  std::map<std::string, int> heading_pages_;
  double keep_with_next_ = 0;  // points of the next block a heading keeps on its page

  double avail() const { return kPageWidth - 2 * kMarginX; }
  double bottom() const { return kPageHeight - kMarginBottom; }

  void font(const char* family, bool bold, double size) {
    cairo_select_font_face(cr_, family, CAIRO_FONT_SLANT_NORMAL,
                           bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr_, size);
  }
  double width(const std::string& s) {
    cairo_text_extents_t e;
    cairo_text_extents(cr_, s.c_str(), &e);
    return e.x_advance;
  }
  void color(double g) { cairo_set_source_rgb(cr_, g, g, g); }
  void text(double x, double baseline, const std::string& s) {
    cairo_move_to(cr_, x, baseline);
    cairo_show_text(cr_, s.c_str());
  }

  // Lines of at most `max` points, broken at spaces (a word longer than a line is cut).
  std::vector<std::string> wrap(const std::string& s, double max) {
    std::vector<std::string> out;
    std::stringstream ss(s);
    std::string word, cur;
    while (ss >> word) {
      const std::string cand = cur.empty() ? word : cur + " " + word;
      if (width(cand) <= max || cur.empty()) {
        cur = cand;
        while (width(cur) > max && cur.size() > 1) {  // an overlong word: cut it
          std::size_t n = cur.size();
          while (n > 1 && width(cur.substr(0, n)) > max) --n;
          out.push_back(cur.substr(0, n));
          cur = cur.substr(n);
        }
      } else {
        out.push_back(cur);
        cur = word;
        while (width(cur) > max && cur.size() > 1) {
          std::size_t n = cur.size();
          while (n > 1 && width(cur.substr(0, n)) > max) --n;
          out.push_back(cur.substr(0, n));
          cur = cur.substr(n);
        }
      }
    }
    if (!cur.empty()) out.push_back(cur);
    if (out.empty()) out.push_back("");
    return out;
  }

  void start_page() {
    ++page_;
    y_ = kMarginTop;
    page_empty_ = true;
  }
  void finish_page() {
    font(kSans, false, 10.5);
    color(0.4);
    text(kMarginX, kPageHeight - 28, doc_.footer);
    const std::string right = "page " + std::to_string(page_) +
                              (numbers_.total ? " of " + std::to_string(numbers_.total) : "");
    text(kPageWidth - kMarginX - width(right), kPageHeight - 28, right);
    cairo_set_line_width(cr_, 0.6);
    cairo_move_to(cr_, kMarginX, kPageHeight - 44);
    cairo_line_to(cr_, kPageWidth - kMarginX, kPageHeight - 44);
    cairo_stroke(cr_);
    color(0);
    cairo_show_page(cr_);
  }
  void new_page() {
    finish_page();
    start_page();
  }
  // Ensures `h` points of space, starting a page when needed.
  void need(double h) {
    if (y_ + h > bottom() && !page_empty_) new_page();
  }

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

  void paragraph(const std::string& s, double size = kBody, double indent = 0,
                 const char* family = kSans, double grey = 0, bool bold = false) {
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

  // --- tables
  struct Fit {
    double size = kTableFont;
    std::vector<double> widths;  // per column, including padding
  };

  double longest_word(const std::string& s) {
    double w = 0;
    std::stringstream ss(s);
    std::string word;
    while (ss >> word) w = std::max(w, width(word));
    return w;
  }

  // Column widths at a font size: each column at least as wide as its widest cell and its
  // header's longest word; the space left over goes to headers that would otherwise wrap,
  // narrowest need first, so that as many as possible stay on one line.
  Fit fit_columns(const Table& t, const std::vector<std::size_t>& cols, double size) {
    Fit f;
    f.size = size;
    const double cap = 0.42 * avail();
    std::vector<double> want;
    for (std::size_t c : cols) {
      font(kSans, false, size);
      double w = 0;
      for (const auto& row : t.rows) w = std::max(w, width(plain_text(row[c])));
      font(kSans, true, size);
      w = std::max(w, longest_word(plain_text(t.header[c])));
      const double full = width(plain_text(t.header[c]));
      f.widths.push_back(std::min(w, cap) + 2 * kPad);
      want.push_back(std::max(w, full) + 2 * kPad);  // no wrapping at all
    }
    double spare = avail() - sum(f.widths);
    std::vector<std::size_t> order(cols.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return want[a] - f.widths[a] < want[b] - f.widths[b];
    });
    for (std::size_t k : order) {
      const double extra = want[k] - f.widths[k];
      if (extra <= 0) continue;
      if (extra > spare) break;
      f.widths[k] = want[k];
      spare -= extra;
    }
    // What is left widens the column that still wraps most.
    if (spare > 0 && !order.empty()) {
      std::size_t most = order.front();
      for (std::size_t k : order)
        if (want[k] - f.widths[k] > want[most] - f.widths[most]) most = k;
      if (want[most] > f.widths[most]) f.widths[most] += std::min(spare, want[most] - f.widths[most]);
    }
    return f;
  }
  static double sum(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return s;
  }

  void table(const Table& t) {
    if (t.header.empty()) {
      if (!t.title.empty()) paragraph(t.title);
      return;
    }
    std::vector<std::size_t> all;
    for (std::size_t c = 0; c < t.header.size(); ++c) all.push_back(c);
    double size = kTableFont;
    Fit f = fit_columns(t, all, size);
    while (sum(f.widths) > avail() && size > kTableFontMin) {
      size -= 0.5;
      f = fit_columns(t, all, size);
    }
    if (sum(f.widths) <= avail()) {
      table_part(t, all, f, "");
    } else {
      // Column groups: the leading key columns (the first, and text columns right after it, at
      // most 3) repeated in each group.
      std::vector<std::size_t> keys = {0};
      for (std::size_t c = 1; c < t.header.size() && c < 3 && !t.right[c]; ++c) keys.push_back(c);
      double key_w = 0;
      for (std::size_t k = 0; k < keys.size(); ++k) key_w += f.widths[keys[k]];
      std::vector<std::vector<std::size_t>> groups;
      double w = key_w;
      for (std::size_t c = keys.size(); c < t.header.size(); ++c) {
        if (groups.empty() || w + f.widths[c] > avail()) {
          groups.push_back(keys);
          w = key_w;
        }
        groups.back().push_back(c);
        w += f.widths[c];
      }
      for (std::size_t g = 0; g < groups.size(); ++g) {
        Fit fg;
        fg.size = f.size;
        for (std::size_t c : groups[g]) fg.widths.push_back(f.widths[c]);
        table_part(t, groups[g], fg,
                   " (part " + std::to_string(g + 1) + " of " + std::to_string(groups.size()) +
                       ": columns " + t.header[groups[g][keys.size()]] + " to " +
                       t.header[groups[g].back()] + ")");
      }
    }
    if (!t.notes.empty()) {
      for (const std::string& n : t.notes) paragraph(n, 11.5, 0, kSans, 0.25);
    }
    y_ += 12;
  }

  void table_part(const Table& t, const std::vector<std::size_t>& cols, const Fit& f,
                  const std::string& suffix) {
    const double size = f.size, lh = size * 1.32;
    const double title_size = 13;
    // The cell lines of every row, wrapped in their columns.
    auto cell_lines = [&](const std::string& s, double w, bool bold) {
      font(kSans, bold, size);
      return wrap(plain_text(s), w - 2 * kPad);
    };
    std::vector<std::vector<std::string>> header_lines;
    std::size_t header_n = 1;
    for (std::size_t k = 0; k < cols.size(); ++k) {
      header_lines.push_back(cell_lines(t.header[cols[k]], f.widths[k], true));
      header_n = std::max(header_n, header_lines.back().size());
    }
    const double header_h = double(header_n) * lh + 2 * kPad;
    const double table_w = sum(f.widths);

    auto draw_title = [&](bool continued) {
      const std::string title = (t.title.empty() ? std::string("Table") : plain_text(t.title)) +
                                suffix + (continued ? " (continued)" : "");
      font(kSans, true, title_size);
      for (const std::string& l : wrap(title, avail())) {
        y_ += title_size * 1.32;
        font(kSans, true, title_size);
        color(0);
        text(kMarginX, y_ - 3, l);
      }
      y_ += 6;
    };
    auto draw_header = [&] {
      cairo_set_source_rgb(cr_, 0.90, 0.92, 0.95);
      cairo_rectangle(cr_, kMarginX, y_, table_w, header_h);
      cairo_fill(cr_);
      color(0);
      cairo_set_line_width(cr_, 1.0);
      cairo_move_to(cr_, kMarginX, y_);
      cairo_line_to(cr_, kMarginX + table_w, y_);
      cairo_stroke(cr_);
      double x = kMarginX;
      for (std::size_t k = 0; k < cols.size(); ++k) {
        font(kSans, true, size);
        for (std::size_t i = 0; i < header_lines[k].size(); ++i) {
          const std::string& l = header_lines[k][i];
          const double tx = t.right[cols[k]] ? x + f.widths[k] - kPad - width(l) : x + kPad;
          text(tx, y_ + kPad + double(i + 1) * lh - size * 0.3, l);
        }
        x += f.widths[k];
      }
      y_ += header_h;
      cairo_move_to(cr_, kMarginX, y_);
      cairo_line_to(cr_, kMarginX + table_w, y_);
      cairo_stroke(cr_);
    };

    // Keep the title, the header and two rows together.
    font(kSans, true, title_size);
    const double title_h = double(wrap(plain_text(t.title) + suffix, avail()).size()) * title_size * 1.32 + 6;
    need(title_h + header_h + 2 * (lh + 2 * kPad) + 8);
    y_ += 4;
    draw_title(false);
    draw_header();
    page_empty_ = false;
    for (std::size_t r = 0; r < t.rows.size(); ++r) {
      std::vector<std::vector<std::string>> lines;
      std::size_t n = 1;
      for (std::size_t k = 0; k < cols.size(); ++k) {
        lines.push_back(cell_lines(t.rows[r][cols[k]], f.widths[k], false));
        n = std::max(n, lines.back().size());
      }
      const double rh = double(n) * lh + 2 * kPad - 2;
      if (y_ + rh > bottom()) {
        new_page();
        draw_title(true);
        draw_header();
        page_empty_ = false;
      }
      if (r % 2 == 1) {
        cairo_set_source_rgb(cr_, 0.965, 0.965, 0.965);
        cairo_rectangle(cr_, kMarginX, y_, table_w, rh);
        cairo_fill(cr_);
        color(0);
      }
      double x = kMarginX;
      font(kSans, false, size);
      for (std::size_t k = 0; k < cols.size(); ++k) {
        for (std::size_t i = 0; i < lines[k].size(); ++i) {
          const std::string& l = lines[k][i];
          const double tx = t.right[cols[k]] ? x + f.widths[k] - kPad - width(l) : x + kPad;
          text(tx, y_ + kPad - 1 + double(i + 1) * lh - size * 0.3, l);
        }
        x += f.widths[k];
      }
      y_ += rh;
    }
    cairo_set_line_width(cr_, 1.0);
    cairo_move_to(cr_, kMarginX, y_);
    cairo_line_to(cr_, kMarginX + table_w, y_);
    cairo_stroke(cr_);
    y_ += 10;
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
