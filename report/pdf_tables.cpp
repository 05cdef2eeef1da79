// Tables on PDF pages (see pdf_tables.h).
#include "report/pdf_tables.h"

#include <algorithm>
#include <sstream>

namespace ra::report {
namespace {

constexpr double kTableFont = 11.5, kTableFontMin = 9;  // points
constexpr double kPad = 5;                               // cell padding, points

double sum(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s;
}

}  // namespace

// A table's font size and its column widths at that size.
struct PdfTables::Fit {
  double size = kTableFont;
  std::vector<double> widths;  // per column, including padding
};

double PdfTables::longest_word(const std::string& s) {
  double w = 0;
  std::stringstream ss(s);
  std::string word;
  while (ss >> word) w = std::max(w, width(word));
  return w;
}

PdfTables::Fit PdfTables::fit_columns(const Table& t, const std::vector<std::size_t>& cols,
                                      double size) {
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
void PdfTables::table(const Table& t) {
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

void PdfTables::table_part(const Table& t, const std::vector<std::size_t>& cols, const Fit& f,
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

}  // namespace ra::report
