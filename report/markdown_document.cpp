// A Markdown file as PDF and HTML (see the header).
#include "report/markdown_document.h"

#include <cctype>
#include <filesystem>
#include <set>

#include "report/document.h"
#include "report/html_writer.h"
#include "report/pdf_writer.h"
#include "util/atomic_file.h"
#include "util/errors.h"

namespace fs = std::filesystem;

namespace ra::report {
namespace {

// "Audit of egl-llvmpipe" -> "audit-of-egl-llvmpipe": lower-case letters, digits and dashes.
std::string anchor_of(const std::string& heading) {
  std::string out;
  for (char c : plain_text(heading)) {
    if (std::isalnum(static_cast<unsigned char>(c)))
      out += char(std::tolower(static_cast<unsigned char>(c)));
    else if (!out.empty() && out.back() != '-')
      out += '-';
  }
  while (!out.empty() && out.back() == '-') out.pop_back();
  return out.empty() ? "section" : out;
}

}  // namespace


MarkdownDocumentResult write_markdown_document(const std::string& markdown_path) {
  std::string text;
  try {
    text = util::read_file(markdown_path);
  } catch (const std::exception& e) {
    throw util::UserError("cannot read " + markdown_path + ": " + e.what());
  }
  const fs::path md(markdown_path);
  Document doc;
  doc.blocks = parse_markdown(text, 0);
  // the first level-1 heading is the title
  for (auto it = doc.blocks.begin(); it != doc.blocks.end(); ++it)
    if (it->kind == Block::Kind::kHeading && it->level == 1) {
      doc.title = plain_text(it->text);
      doc.blocks.erase(it);
      break;
    }
  if (doc.title.empty()) doc.title = md.stem().string();
  doc.subtitle = {"From " + md.string()};
  doc.footer = doc.title + " (" + md.filename().string() + ")";
  MarkdownDocumentResult r;
  const auto resolve = [&](const std::string& href) {
    const std::string path = (md.parent_path() / href).string();
    ++r.pictures;
    r.missing_pictures += !fs::exists(path);
    return path;
  };
  std::set<std::string> anchors;
  for (Block& b : doc.blocks) {
    if (b.kind == Block::Kind::kImage && b.row.empty()) b.image_path = resolve(b.image_href);
    for (Picture& p : b.row) p.path = resolve(p.href);
    // every heading an anchor of the HTML (and its level-1 ones an entry of [TOC])
    if (b.kind == Block::Kind::kHeading && b.anchor.empty()) {
      const std::string base = anchor_of(b.text);
      b.anchor = base;
      for (int n = 2; !anchors.insert(b.anchor).second; ++n) b.anchor = base + "-" + std::to_string(n);
    }
  }
  r.pdf = (md.parent_path() / (md.stem().string() + ".pdf")).string();
  r.html = (md.parent_path() / (md.stem().string() + ".html")).string();
  const std::string tmp = r.pdf + ".tmp";
  // laid out once to learn the pages of its sections (the table of contents), then written
  const PdfLayoutResult layout = write_text_pdf(doc, "", {});
  PageNumbers numbers;
  numbers.total = layout.pages;
  numbers.heading_pages = layout.heading_pages;
  r.pages = write_text_pdf(doc, tmp, numbers).pages;
  std::error_code ec;
  fs::rename(tmp, r.pdf, ec);
  if (ec) throw util::UserError("cannot write " + r.pdf + ": " + ec.message());
  util::write_file_atomic(r.html, render_html(doc));
  return r;
}

}  // namespace ra::report
