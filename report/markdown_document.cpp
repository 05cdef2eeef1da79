// A Markdown file as PDF and HTML (see the header).
#include "report/markdown_document.h"

#include <filesystem>

#include "report/document.h"
#include "report/html_writer.h"
#include "report/pdf_writer.h"
#include "util/atomic_file.h"
#include "util/errors.h"

namespace fs = std::filesystem;

namespace ra::report {

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
  for (Block& b : doc.blocks)
    if (b.kind == Block::Kind::kImage) {
      b.image_path = (md.parent_path() / b.image_href).string();
      ++r.pictures;
      r.missing_pictures += !fs::exists(b.image_path);
    }
  r.pdf = (md.parent_path() / (md.stem().string() + ".pdf")).string();
  r.html = (md.parent_path() / (md.stem().string() + ".html")).string();
  const std::string tmp = r.pdf + ".tmp";
  r.pages = write_text_pdf(doc, tmp, {}).pages;
  std::error_code ec;
  fs::rename(tmp, r.pdf, ec);
  if (ec) throw util::UserError("cannot write " + r.pdf + ": " + ec.message());
  util::write_file_atomic(r.html, render_html(doc));
  return r;
}

}  // namespace ra::report
