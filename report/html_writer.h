// The report as one HTML file: the same blocks as the PDF (document.h), figures as <img> of the
// PNGs with links to their vector PDFs (paths relative to the report directory, so the run
// directory can be moved or copied as a whole).
#pragma once

#include <string>

#include "report/document.h"

namespace ra::report {

std::string render_html(const Document& doc);

// Escapes &, <, >, " for HTML text and attributes.
std::string html_escape(const std::string& s);

}  // namespace ra::report
