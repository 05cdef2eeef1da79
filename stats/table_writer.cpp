// CSV, Markdown and LaTeX renderings of one table model; see table_writer.h.
#include "stats/table_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <regex>
#include <stdexcept>

#include "stats/binomial_interval.h"
#include "util/number_text.h"

namespace ra::stats {
namespace {

// Column header text of CSV and Markdown: the group label joined to the column name.
std::vector<std::string> flat_header(const Table& t) {
  std::vector<std::string> names;
  std::size_t column = 0;
  const std::vector<ColumnGroup> groups =
      t.groups.empty() ? std::vector<ColumnGroup>{{"", t.columns.size()}} : t.groups;
  for (const ColumnGroup& g : groups) {
    for (std::size_t i = 0; i < g.span; ++i, ++column) {
      const std::string& name = t.columns[column].name;
      names.push_back(g.label.empty() ? name : g.label + " " + name);
    }
  }
  return names;
}

void require_finite(double value, const char* what) {
  if (!std::isfinite(value)) {
    throw std::logic_error(std::string("table_writer: ") + what +
                           ": a non-finite number reached a table (a bug: undefined values must "
                           "be text cells)");
  }
}

}  // namespace

TableCell text_cell(std::string text) { return TableCell{std::move(text), ""}; }

std::string format_fixed(double value, int decimals) {
  require_finite(value, "format_fixed");
  std::string s = util::fixed(value, decimals);
  if (s[0] == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);
  return s;
}

std::string format_significant(double value, int significant) {
  require_finite(value, "format_significant");
  return util::significant(value == 0 ? 0.0 : value, significant);
}

TableCell number_cell(double value, int decimals) {
  return TableCell{format_fixed(value, decimals), format_significant(value, 9)};
}

TableCell significant_cell(double value, int significant) {
  return TableCell{format_significant(value, significant), format_significant(value, 9)};
}

TableCell count_cell(std::uint64_t n) { return text_cell(std::to_string(n)); }

TableCell share_cell(std::uint64_t k, std::uint64_t n) {
  const stats::ProportionInterval ci = stats::clopper_pearson(k, n);
  const double share = n ? 100.0 * double(k) / double(n) : 0.0;
  return {format_fixed(share, 2) + " (" + format_fixed(100 * ci.low, 2) + "-" +
              format_fixed(100 * ci.high, 2) + ")",
          format_significant(share, 9)};
}

void add_columns(Table& table, const std::vector<std::string>& names, Align align) {
  for (const std::string& name : names) table.columns.push_back({name, align});
}

void check_table(const Table& t) {
  if (t.columns.empty()) throw std::logic_error("table " + t.file_stem + ": no columns");
  if (!t.groups.empty()) {
    std::size_t spans = 0;
    for (const ColumnGroup& g : t.groups) spans += g.span;
    if (spans != t.columns.size()) {
      throw std::logic_error("table " + t.file_stem + ": column groups span " +
                             std::to_string(spans) + " of " + std::to_string(t.columns.size()) +
                             " columns");
    }
  }
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    if (t.rows[r].size() != t.columns.size()) {
      throw std::logic_error("table " + t.file_stem + ": row " + std::to_string(r) + " has " +
                             std::to_string(t.rows[r].size()) + " cells for " +
                             std::to_string(t.columns.size()) + " columns");
    }
  }
}

std::string markdown_escape(const std::string& text) {
  std::string s;
  for (char c : text) {
    if (c == '|') s += '\\';
    s += c == '\n' ? ' ' : c;
  }
  return s;
}

std::string latex_escape(const std::string& text) {
  std::string s;
  for (char c : text) {
    switch (c) {
      case '\\':
        s += "\\textbackslash{}";
        break;
      case '&':
      case '%':
      case '$':
      case '#':
      case '_':
      case '{':
      case '}':
        s += '\\';
        s += c;
        break;
      case '~':
        s += "\\textasciitilde{}";
        break;
      case '^':
        s += "\\textasciicircum{}";
        break;
      case '\n':
        s += ' ';
        break;
      default:
        s += c;
    }
  }
  return s;
}

namespace {

// Escaped text with the scale notation "x10^6" of titles and notes typeset as $\times 10^{6}$.
std::string latex_text(const std::string& text) {
  static const std::regex scale(R"(x10\\textasciicircum\{\}(-?[0-9]+))");
  return std::regex_replace(latex_escape(text), scale, "$\\times 10^{$1}$$");
}

}  // namespace

std::string render_csv(const Table& t) {
  check_table(t);
  std::string out = "# " + t.title + "\n";
  for (const std::string& note : t.notes) out += "# " + note + "\n";
  const std::vector<std::string> header = flat_header(t);
  for (std::size_t c = 0; c < header.size(); ++c)
    out += (c ? "," : "") + util::csv_escape(header[c]);
  out += "\n";
  for (const auto& row : t.rows) {
    for (std::size_t c = 0; c < row.size(); ++c) {
      out += (c ? "," : "") + util::csv_escape(row[c].csv.empty() ? row[c].text : row[c].csv);
    }
    out += "\n";
  }
  return out;
}

std::string render_markdown(const Table& t) {
  check_table(t);
  std::string out = "### " + t.title + "\n\n";
  std::vector<Align> align;
  for (const TableColumn& c : t.columns) align.push_back(c.align);
  out += markdown_header(flat_header(t), align);
  for (const auto& row : t.rows) {
    std::vector<std::string> cells;
    for (const TableCell& cell : row) cells.push_back(cell.text);
    out += markdown_row(cells);
  }
  if (!t.notes.empty()) {
    out += "\n";
    for (const std::string& note : t.notes) out += "- " + note + "\n";
  }
  return out;
}

std::string markdown_row(const std::vector<std::string>& cells) {
  std::string out = "|";
  for (const std::string& cell : cells) out += " " + markdown_escape(cell) + " |";
  return out + "\n";
}

std::string markdown_header(const std::vector<std::string>& names, const std::vector<Align>& align) {
  if (align.size() != names.size())
    throw std::logic_error("markdown_header: " + std::to_string(names.size()) + " names, " +
                           std::to_string(align.size()) + " alignments");
  return markdown_row(names) + markdown_rule(align);
}

std::string markdown_rule(const std::vector<Align>& align) {
  std::string out = "|";
  for (const Align a : align) {
    switch (a) {
      case Align::kLeft: out += " :--- |"; break;
      case Align::kRight: out += " ---: |"; break;
      case Align::kCenter: out += " :---: |"; break;
      case Align::kDefault: out += " --- |"; break;
    }
  }
  return out + "\n";
}

std::string markdown_compact_rule(std::size_t columns) {
  std::string out = "|";
  for (std::size_t i = 0; i < columns; ++i) out += "---|";
  return out + "\n";
}

std::string markdown_header(const std::vector<std::string>& names, std::size_t left_columns) {
  std::vector<Align> align;
  for (std::size_t i = 0; i < names.size(); ++i)
    align.push_back(i < left_columns ? Align::kDefault : Align::kRight);
  return markdown_header(names, align);
}

std::string render_latex(const Table& t) {
  check_table(t);
  std::string out =
      "% " + t.title + "\n% Written by renderaudit analyze; needs \\usepackage{booktabs}.\n";
  out += "\\begin{table}[htbp]\n\\centering\n";
  out += "\\caption{" + (t.latex_title.empty() ? latex_text(t.title) : t.latex_title) + "}\n";
  out += "\\label{tab:" + t.file_stem + "}\n";  // labels take '_' as it is
  out += "\\begin{tabular}{";
  for (const TableColumn& c : t.columns)
    out += c.align == Align::kRight ? 'r' : c.align == Align::kCenter ? 'c' : 'l';
  out += "}\n\\toprule\n";
  if (!t.groups.empty()) {
    std::string rules;
    std::size_t first = 1;
    for (std::size_t g = 0; g < t.groups.size(); ++g) {
      const ColumnGroup& group = t.groups[g];
      out += (g ? " & " : "") + std::string("\\multicolumn{") + std::to_string(group.span) +
             "}{c}{" + latex_escape(group.label) + "}";
      if (!group.label.empty()) {
        rules += (rules.empty() ? "" : " ") + std::string("\\cmidrule(lr){") +
                 std::to_string(first) + "-" + std::to_string(first + group.span - 1) + "}";
      }
      first += group.span;
    }
    out += " \\\\\n";
    if (!rules.empty()) out += rules + "\n";
  }
  for (std::size_t c = 0; c < t.columns.size(); ++c) {
    out += (c ? " & " : "") + latex_escape(t.columns[c].name);
  }
  out += " \\\\\n\\midrule\n";
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    if (r != 0 &&
        std::find(t.rules_before.begin(), t.rules_before.end(), r) != t.rules_before.end()) {
      out += "\\midrule\n";
    }
    for (std::size_t c = 0; c < t.rows[r].size(); ++c) {
      out += (c ? " & " : "") + latex_escape(t.rows[r][c].text);
    }
    out += " \\\\\n";
  }
  out += "\\bottomrule\n\\end{tabular}\n";
  if (!t.notes.empty()) {
    out += "\n\\smallskip\n{\\footnotesize\n";
    for (const std::string& note : t.notes) out += latex_text(note) + "\\par\n";
    out += "}\n";
  }
  out += "\\end{table}\n";
  return out;
}

}  // namespace ra::stats
