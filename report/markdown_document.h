// A Markdown file as a document like the run reports: FILE.pdf (cairo, the report's page size
// and type) and FILE.html beside FILE.md, its pictures ("![caption](path)", relative to the file;
// several on one line side by side) set in the text. Every heading gets an HTML anchor (its words
// in lower case joined by dashes, "audit-of-egl-llvmpipe"); a line "[TOC]" lists the level-1
// headings with their pages (PDF) or links (HTML). Used for the driver upgrade's report
// (scripts/driver-upgrade.sh).
#pragma once

#include <string>

namespace ra::report {

struct MarkdownDocumentResult {
  std::string pdf, html;
  int pages = 0;
  int pictures = 0, missing_pictures = 0;  // pictures named; of those, files not found
};

// The document's title is the file's first "# " heading. Throws util::UserError when the file
// cannot be read or the PDF cannot be written.
MarkdownDocumentResult write_markdown_document(const std::string& markdown_path);

}  // namespace ra::report
