// The Markdown reader and the CSV table reader of the report (see document.h).
#include "report/document.h"

#include <algorithm>
#include <sstream>

#include "stats/csv_table.h"
#include "util/atomic_file.h"
#include "util/errors.h"

namespace ra::report {
namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

// Cells of a pipe-table row; "\|" is a literal bar.
std::vector<std::string> split_row(const std::string& line) {
  std::string s = trim(line);
  if (!s.empty() && s.front() == '|') s.erase(0, 1);
  if (!s.empty() && s.back() == '|' && (s.size() < 2 || s[s.size() - 2] != '\\')) s.pop_back();
  std::vector<std::string> cells;
  std::string cur;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '\\' && i + 1 < s.size() && s[i + 1] == '|') {
      cur += '|';
      ++i;
    } else if (s[i] == '|') {
      cells.push_back(trim(cur));
      cur.clear();
    } else {
      cur += s[i];
    }
  }
  cells.push_back(trim(cur));
  return cells;
}

bool is_alignment_row(const std::string& line) {
  const std::string s = trim(line);
  if (s.empty() || s.front() != '|') return false;
  for (char c : s)
    if (c != '|' && c != '-' && c != ':' && c != ' ') return false;
  return s.find('-') != std::string::npos;
}

// The pictures of a line "![a](p) ![b](q)" (nothing else on it), hrefs as written; none if the
// line holds anything else.
std::vector<Picture> pictures_of(const std::string& line) {
  std::vector<Picture> out;
  std::size_t at = 0;
  while (at < line.size()) {
    if (line.compare(at, 2, "![") != 0) return {};
    const std::size_t close = line.find("](", at);
    const std::size_t end = close == std::string::npos ? close : line.find(')', close);
    if (end == std::string::npos) return {};
    out.push_back({"", line.substr(close + 2, end - close - 2), line.substr(at + 2, close - at - 2)});
    at = line.find_first_not_of(" \t", end + 1);
  }
  return out;
}

}  // namespace

std::string plain_text(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text.compare(i, 2, "**") == 0) {
      ++i;
      continue;
    }
    if (text[i] == '`') continue;
    out += text[i];
  }
  return out;
}

std::vector<Block> parse_markdown(const std::string& markdown, int heading_offset) {
  std::vector<std::string> lines;
  {
    std::stringstream ss(markdown);
    std::string l;
    while (std::getline(ss, l)) {
      if (!l.empty() && l.back() == '\r') l.pop_back();
      lines.push_back(l);
    }
  }
  std::vector<Block> blocks;
  std::string paragraph;
  auto flush_paragraph = [&] {
    if (!paragraph.empty()) {
      Block b;
      b.kind = Block::Kind::kParagraph;
      b.text = paragraph;
      blocks.push_back(b);
      paragraph.clear();
    }
  };
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string line = trim(lines[i]);
    if (line.empty()) {
      flush_paragraph();
      continue;
    }
    // A fenced block: its lines as they are, to the closing fence (or the end).
    if (line.rfind("```", 0) == 0) {
      flush_paragraph();
      Block b;
      b.kind = Block::Kind::kPreformatted;
      for (++i; i < lines.size() && trim(lines[i]).rfind("```", 0) != 0; ++i)
        b.text += (b.text.empty() ? "" : "\n") + lines[i];
      blocks.push_back(b);
      continue;
    }
    if (line == "[TOC]") {
      flush_paragraph();
      Block b;
      b.kind = Block::Kind::kContents;
      blocks.push_back(b);
      continue;
    }
    if (line[0] == '#') {
      flush_paragraph();
      std::size_t level = 0;
      while (level < line.size() && line[level] == '#') ++level;
      const std::string text = trim(line.substr(level));
      // A "###" title directly followed (after blank lines) by a table is the table's title.
      std::size_t j = i + 1;
      while (j < lines.size() && trim(lines[j]).empty()) ++j;
      if (level >= 3 && j + 1 < lines.size() && trim(lines[j]).rfind('|', 0) == 0 &&
          is_alignment_row(lines[j + 1])) {
        Block b;
        b.kind = Block::Kind::kTable;
        b.table.title = text;
        blocks.push_back(b);
        i = j - 1;
        continue;
      }
      Block b;
      b.kind = Block::Kind::kHeading;
      b.level = std::min(3, int(level) + heading_offset);
      b.text = text;
      blocks.push_back(b);
      continue;
    }
    if (line[0] == '|' && i + 1 < lines.size() && is_alignment_row(lines[i + 1])) {
      flush_paragraph();
      // Attach to a title-only table block just made, else start an untitled table.
      if (blocks.empty() || blocks.back().kind != Block::Kind::kTable ||
          !blocks.back().table.header.empty()) {
        Block b;
        b.kind = Block::Kind::kTable;
        blocks.push_back(b);
      }
      Table& t = blocks.back().table;
      t.header = split_row(line);
      for (const std::string& a : split_row(lines[i + 1]))
        t.right.push_back(!a.empty() && a.back() == ':' && a.front() != ':');
      t.right.resize(t.header.size(), false);
      i += 2;
      for (; i < lines.size() && trim(lines[i]).rfind('|', 0) == 0; ++i) {
        std::vector<std::string> cells = split_row(lines[i]);
        cells.resize(t.header.size());
        t.rows.push_back(std::move(cells));
      }
      // Notes: a "- " list right after the table.
      std::size_t j = i;
      while (j < lines.size() && trim(lines[j]).empty()) ++j;
      if (j < lines.size() && trim(lines[j]).rfind("- ", 0) == 0) {
        for (i = j; i < lines.size() && trim(lines[i]).rfind("- ", 0) == 0; ++i)
          t.notes.push_back(trim(lines[i]).substr(2));
      }
      --i;
      continue;
    }
    if (line.rfind("- ", 0) == 0 || line.rfind("* ", 0) == 0) {
      flush_paragraph();
      if (blocks.empty() || blocks.back().kind != Block::Kind::kBullets ||
          (i > 0 && trim(lines[i - 1]).empty())) {
        Block b;
        b.kind = Block::Kind::kBullets;
        blocks.push_back(b);
      }
      blocks.back().items.push_back(line.substr(2));
      continue;
    }
    // Pictures on a line of their own: ![caption](path, relative to the Markdown file), one or
    // several side by side
    if (line.rfind("![", 0) == 0 && line.back() == ')') {
      const std::vector<Picture> pictures = pictures_of(line);
      if (pictures.size() == 1) {
        flush_paragraph();
        Block b;
        b.kind = Block::Kind::kImage;
        b.text = pictures[0].caption;
        b.image_href = pictures[0].href;
        blocks.push_back(b);
        continue;
      }
      if (pictures.size() > 1) {
        flush_paragraph();
        Block b;
        b.kind = Block::Kind::kImage;
        b.row = pictures;
        b.image_height_fraction = 0.62;  // side by side, each is narrow: let them be tall
        blocks.push_back(b);
        continue;
      }
    }
    // A continuation line of a list item (indented) or of a paragraph.
    if (!blocks.empty() && blocks.back().kind == Block::Kind::kBullets && paragraph.empty() &&
        (lines[i][0] == ' ' || lines[i][0] == '\t')) {
      blocks.back().items.back() += " " + line;
      continue;
    }
    paragraph += (paragraph.empty() ? "" : " ") + line;
  }
  flush_paragraph();
  return blocks;
}

Table read_csv_table(const std::string& path) {
  std::string text;
  try {
    text = util::read_file(path);
  } catch (const std::exception& e) {
    throw util::UserError(std::string("cannot read ") + path + ": " + e.what());
  }
  Table t;
  std::stringstream ss(text);
  std::string line, rest;
  std::size_t comment_lines = 0;
  while (std::getline(ss, line)) {
    if (line.rfind("# ", 0) == 0 || line == "#") {
      const std::string body = trim(line.substr(1));
      if (t.title.empty())
        t.title = body;
      else
        t.notes.push_back(body);
      ++comment_lines;
      continue;
    }
    rest = line + "\n";
    break;
  }
  std::stringstream tail;
  tail << ss.rdbuf();
  rest += tail.str();
  const auto csv = stats::CsvTable::parse(rest, path);
  t.header = csv.header();
  t.right.assign(t.header.size(), true);
  for (std::size_t r = 0; r < csv.row_count(); ++r) {
    std::vector<std::string> row;
    for (std::size_t c = 0; c < csv.column_count(); ++c) {
      const std::string& cell = csv.cell(r, c);
      if (!cell.empty() && !stats::parse_number(cell)) t.right[c] = false;
      row.push_back(cell);
    }
    t.rows.push_back(std::move(row));
  }
  return t;
}

}  // namespace ra::report
