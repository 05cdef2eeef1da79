// The report as a document model, rendered twice from the same blocks: as PDF pages (cairo,
// pdf_writer.h) and as HTML (html_writer.h), so the two cannot disagree.
//
// Text comes from the analysis stage's Markdown files (DIR/analysis/*.md) through a small
// Markdown reader (parse_markdown) that knows what those files use: #-headings, paragraphs,
// "- " lists, pipe tables with an alignment row, **bold** and `code` spans (kept as plain text in
// the PDF, as <b> and <code> in HTML).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace ra::report {

struct Table {
  std::string title;                      // one line (may be long: wrapped when drawn)
  std::vector<std::string> header;        // column names
  std::vector<bool> right;                // right-aligned columns (numbers)
  std::vector<std::vector<std::string>> rows;  // each header.size() cells
  std::vector<std::string> notes;         // sentences under the table
};

// One picture of a row of pictures set side by side (Block::row).
struct Picture {
  std::string path;     // the PNG (absolute, for the PDF)
  std::string href;     // the PNG relative to the report directory (HTML)
  std::string caption;  // under this picture
};

struct Block {
  enum class Kind {
    kHeading,       // text, level 1-3
    kParagraph,     // text
    kBullets,       // items
    kTable,         // table
    kPreformatted,  // text (monospace, lines kept)
    kFigureList,    // the list of figures (Document::figures) with their pages
    kContents,      // the list of level-1 headings with their pages
    kPageBreak,
    kImage,         // a PNG in the text (image_path; HTML: image_href), `text` its caption;
                    // or, where `row` is not empty, its pictures side by side, `text` under all
    kNotes,         // items, in the small grey type of a table's notes
  };
  Kind kind = Kind::kParagraph;
  int level = 1;
  std::string text;
  std::vector<std::string> items;
  Table table;
  std::string anchor;  // HTML id of a heading
  std::string image_path;  // kImage: the PNG (absolute, for the PDF)
  std::string image_href;  // kImage: the PNG relative to the report directory (HTML)
  double image_height_fraction = 0.42;  // kImage: at most this share of the page's height (PDF)
  std::vector<Picture> row;  // kImage: pictures side by side (then image_path is unused)
};

struct FigureRef {
  int number = 0;  // 1-based
  std::string id, section, title, caption, note;
  std::string png, pdf;  // paths relative to the report directory (../figures/ID.png)
  std::string pdf_path;  // absolute path of the figure's PDF (for assembling)
};

struct Document {
  std::string title;
  std::vector<std::string> subtitle;  // lines under the title
  std::string footer;                 // left part of each page's footer
  std::vector<Block> blocks;
  std::vector<FigureRef> figures;     // placed after the text, one page each, in this order
};

// Blocks of a Markdown text (see the header comment). Headings are shifted down by
// `heading_offset` levels (a file's "#" becomes level 1 + offset) and capped at 3. A "###" heading
// directly followed by a pipe table becomes the table's title. A line "![caption](path)" is a
// picture (kImage, image_href = path; the caller resolves image_path); a line of several such
// pictures is a row of them side by side (Block::row). A fenced block (lines between two "```"
// lines) is kept line by line (kPreformatted); a line "[TOC]" is the table of contents
// (kContents).
std::vector<Block> parse_markdown(const std::string& markdown, int heading_offset = 0);

// `text` without Markdown emphasis (** and `), for the PDF.
std::string plain_text(const std::string& text);

// A table from a CSV file of the analysis stage: leading "# " lines are the title (first) and the
// notes; then a header row and the rows (RFC 4180 quoting). Columns whose cells all parse as
// numbers (or are empty) are right-aligned. Throws ra::util::UserError on unreadable or malformed CSV.
Table read_csv_table(const std::string& path);

}  // namespace ra::report
