// HTML rendering of the report document (see html_writer.h).
#include "report/html_writer.h"

#include <sstream>

namespace ra::report {
namespace {

// Escaped text with **bold** and `code` spans.
std::string inline_html(const std::string& s) {
  std::string out;
  bool bold = false, code = false;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!code && s.compare(i, 2, "**") == 0) {
      out += bold ? "</b>" : "<b>";
      bold = !bold;
      ++i;
    } else if (s[i] == '`') {
      out += code ? "</code>" : "<code>";
      code = !code;
    } else {
      out += html_escape(std::string(1, s[i]));
    }
  }
  if (code) out += "</code>";
  if (bold) out += "</b>";
  return out;
}

void table_html(std::ostringstream& o, const Table& t) {
  o << "<table>\n";
  if (!t.title.empty()) o << "<caption>" << inline_html(t.title) << "</caption>\n";
  o << "<thead><tr>";
  for (std::size_t c = 0; c < t.header.size(); ++c)
    o << "<th" << (t.right[c] ? " class=\"num\"" : "") << ">" << inline_html(t.header[c]) << "</th>";
  o << "</tr></thead>\n<tbody>\n";
  for (const auto& row : t.rows) {
    o << "<tr>";
    for (std::size_t c = 0; c < row.size(); ++c)
      o << "<td" << (t.right[c] ? " class=\"num\"" : "") << ">" << inline_html(row[c]) << "</td>";
    o << "</tr>\n";
  }
  o << "</tbody></table>\n";
  if (!t.notes.empty()) {
    o << "<ul class=\"notes\">\n";
    for (const auto& n : t.notes) o << "<li>" << inline_html(n) << "</li>\n";
    o << "</ul>\n";
  }
}

}  // namespace

std::string html_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string render_html(const Document& doc) {
  // The figures get an anchor of their own only where no heading already has id="figures".
  bool figures_heading = false;
  for (const Block& b : doc.blocks)
    figures_heading = figures_heading || (b.kind == Block::Kind::kHeading && b.anchor == "figures");
  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>"
    << html_escape(doc.title) << "</title>\n<style>\n"
    << "body{font-family:'DejaVu Sans',Arial,sans-serif;max-width:1200px;margin:2em auto;"
       "padding:0 1em;line-height:1.45;color:#111}\n"
       "h1{border-bottom:2px solid #333;margin-top:2em}h2{margin-top:1.6em}\n"
       "table{border-collapse:collapse;margin:1em 0;font-size:0.9em}\n"
       "caption{caption-side:top;text-align:left;font-weight:bold;padding:0.3em 0}\n"
       "th,td{padding:0.25em 0.6em;border-bottom:1px solid #ccc;vertical-align:top}\n"
       "th{background:#e6ebf2;text-align:left}\n.num{text-align:right}\n"
       "tbody tr:nth-child(even){background:#f6f6f6}\n"
       "ul.notes{font-size:0.88em;color:#333}\n"
       "figure{margin:2em 0;page-break-inside:avoid}figure img{max-width:100%;border:1px solid #ddd}\n"
       "figcaption{font-size:0.92em;margin-top:0.4em}\npre{background:#f4f4f4;padding:0.8em;"
       "overflow-x:auto}\n.subtitle{color:#555}\n"
       ".row{display:flex;gap:1.5em}.row figure{flex:1;margin:1em 0}\n</style>\n</head>\n<body>\n";
  o << "<h1 class=\"title\">" << html_escape(doc.title) << "</h1>\n";
  for (const auto& s : doc.subtitle) o << "<p class=\"subtitle\">" << inline_html(s) << "</p>\n";
  for (const Block& b : doc.blocks) {
    switch (b.kind) {
      case Block::Kind::kHeading: {
        const int level = b.level < 1 ? 1 : b.level > 3 ? 3 : b.level;
        o << "<h" << level << (b.anchor.empty() ? "" : " id=\"" + html_escape(b.anchor) + "\"")
          << ">" << inline_html(b.text) << "</h" << level << ">\n";
        break;
      }
      case Block::Kind::kParagraph: o << "<p>" << inline_html(b.text) << "</p>\n"; break;
      case Block::Kind::kBullets:
        o << "<ul>\n";
        for (const auto& i : b.items) o << "<li>" << inline_html(i) << "</li>\n";
        o << "</ul>\n";
        break;
      case Block::Kind::kTable: table_html(o, b.table); break;
      case Block::Kind::kPreformatted: o << "<pre>" << html_escape(b.text) << "</pre>\n"; break;
      case Block::Kind::kContents: {
        o << "<ul>\n";
        for (const Block& h : doc.blocks)
          if (h.kind == Block::Kind::kHeading && h.level == 1 && !h.anchor.empty())
            o << "<li><a href=\"#" << html_escape(h.anchor) << "\">" << inline_html(h.text)
              << "</a></li>\n";
        if (!doc.figures.empty() && !figures_heading)
          o << "<li><a href=\"#figures\">Figures</a></li>\n";
        o << "</ul>\n";
        break;
      }
      case Block::Kind::kFigureList: {
        if (!figures_heading) o << "<div id=\"figures\"></div>\n";
        if (doc.figures.empty()) o << "<p>No figure was drawn.</p>\n";
        std::string section;
        for (const FigureRef& f : doc.figures) {
          if (f.section != section) {
            section = f.section;
            o << "<h2>Figures: " << html_escape(section) << "</h2>\n";
          }
          o << "<figure id=\"" << html_escape(f.id) << "\">\n<a href=\"" << html_escape(f.pdf)
            << "\"><img src=\"" << html_escape(f.png) << "\" alt=\"" << html_escape(f.title)
            << "\" loading=\"lazy\"></a>\n<figcaption><b>Figure " << f.number << ".</b> "
            << inline_html(f.title) << ". " << inline_html(f.caption);
          o << " <a href=\"" << html_escape(f.pdf) << "\">PDF</a></figcaption>\n</figure>\n";
        }
        break;
      }
      case Block::Kind::kPageBreak: break;
      case Block::Kind::kNotes:
        o << "<ul class=\"notes\">\n";
        for (const auto& n : b.items) o << "<li>" << inline_html(n) << "</li>\n";
        o << "</ul>\n";
        break;
      case Block::Kind::kImage:
        if (!b.row.empty()) {  // side by side, each with its caption
          o << "<div class=\"row\">\n";
          for (const Picture& p : b.row)
            o << "<figure>\n<img src=\"" << html_escape(p.href) << "\" alt=\""
              << html_escape(plain_text(p.caption)) << "\">\n<figcaption>" << inline_html(p.caption)
              << "</figcaption>\n</figure>\n";
          o << "</div>\n";
          if (!b.text.empty()) o << "<p class=\"subtitle\">" << inline_html(b.text) << "</p>\n";
          break;
        }
        o << "<figure>\n<img src=\"" << html_escape(b.image_href) << "\" alt=\""
          << html_escape(plain_text(b.text)) << "\">\n<figcaption>" << inline_html(b.text)
          << "</figcaption>\n</figure>\n";
        break;
    }
  }
  o << "</body>\n</html>\n";
  return o.str();
}

}  // namespace ra::report
