// renderaudit's help layout (see the header).
#include "app/help_format.h"

#include <algorithm>
#include <map>
#include <memory>
#include <sstream>
#include <vector>

namespace ra::app {

std::string wrap_text(const std::string& text, std::size_t width, std::size_t indent) {
  std::string out;
  std::istringstream lines(text);
  std::string line;
  bool first = true;
  while (std::getline(lines, line)) {
    if (!first) out += '\n';
    first = false;
    if (line.size() <= width) {
      out += line;
      continue;
    }
    const std::size_t lead = line.find_first_not_of(' ') == std::string::npos
                                 ? 0
                                 : line.find_first_not_of(' ');
    std::string rest = line;
    std::string pad(lead + indent, ' ');
    while (rest.size() > width) {
      std::size_t cut = rest.rfind(' ', width);
      if (cut == std::string::npos || cut <= pad.size()) cut = rest.find(' ', width);
      if (cut == std::string::npos) break;  // one word longer than the line: left whole
      out += rest.substr(0, cut) + '\n';
      std::size_t next = rest.find_first_not_of(' ', cut);
      rest = pad + (next == std::string::npos ? "" : rest.substr(next));
    }
    out += rest;
  }
  if (!text.empty() && text.back() == '\n') out += '\n';
  return out;
}

namespace {

std::string collapse_spaces(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '\n' || c == '\t') c = ' ';
    if (c == ' ' && (out.empty() || out.back() == ' ')) continue;
    out += c;
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

std::string without_parentheses(const std::string& s) {
  std::string out;
  int depth = 0;
  for (char c : s) {
    if (c == '(') ++depth;
    if (depth == 0) out += c;
    if (c == ')' && depth > 0) --depth;
  }
  out = collapse_spaces(out);
  for (std::size_t at; (at = out.find(" ,")) != std::string::npos;) out.erase(at, 1);
  return out;
}

}  // namespace

std::string command_summary(const std::string& description, std::size_t width) {
  std::string s = collapse_spaces(description);
  // The first sentence: up to ". " (a period followed by a space), or all of it.
  for (std::size_t at = s.find(". "); at != std::string::npos; at = s.find(". ", at + 1)) {
    // "e.g. " and "i.e. " do not end a sentence
    if (at >= 3 && (s.compare(at - 3, 3, "e.g") == 0 || s.compare(at - 3, 3, "i.e") == 0))
      continue;
    s = s.substr(0, at);
    break;
  }
  if (!s.empty() && s.back() == '.') s.pop_back();
  if (s.size() > width && s.find(": ") != std::string::npos) s = s.substr(0, s.find(": "));
  if (s.size() > width) s = without_parentheses(s);
  while (s.size() > width && s.rfind(", ") != std::string::npos) s = s.substr(0, s.rfind(", "));
  if (s.size() > width) s = s.substr(0, s.rfind(' ', width - 3)) + "...";
  return s;
}

namespace {

class HelpFormatter : public CLI::Formatter {
 public:
  HelpFormatter() { column_width(30); }

  std::string make_usage(const CLI::App* app, std::string) const override {
    std::string name;
    for (const CLI::App* a = app; a; a = a->get_parent())
      name = (a->get_parent() ? a->get_name() : std::string("renderaudit")) +
             (name.empty() ? "" : " " + name);
    std::string out = "Usage: " + name;
    if (!app->get_options([](const CLI::Option* o) { return o->nonpositional(); }).empty())
      out += " [OPTIONS]";
    for (const CLI::Option* o : app->get_options([](const CLI::Option* o) { return o->get_positional(); }))
      out += " " + make_option_usage(o);
    if (!app->get_subcommands([](const CLI::App* s) { return !s->get_disabled() && !s->get_name().empty(); })
             .empty())
      out += app->get_require_subcommand_min() == 0 ? " [COMMAND]" : " COMMAND";
    return wrap_text(out, kHelpWidth, 4) + "\n";
  }

  // Usage first, then what the command does, its arguments, options and commands.
  std::string make_help(const CLI::App* app, std::string name, CLI::AppFormatMode mode) const override {
    if (mode == CLI::AppFormatMode::Sub) return make_expanded(app);
    std::string out = make_usage(app, name);
    const std::string d = make_description(app);
    if (!d.empty()) out += "\n" + d;
    out += make_positionals(app) + make_groups(app, mode) + make_subcommands(app, mode);
    const std::string footer = make_footer(app);
    if (!footer.empty()) out += "\n" + footer;
    return out;
  }

  std::string make_description(const CLI::App* app) const override {
    const std::string d = app->get_description();
    return d.empty() ? "" : wrap_text(d, kHelpWidth) + "\n";
  }

  std::string make_subcommands(const CLI::App* app, CLI::AppFormatMode mode) const override {
    const std::string list = CLI::Formatter::make_subcommands(app, mode);
    return list.empty() ? list : "\nCommands:" + list.substr(list.find(':') + 1);
  }

  std::string make_subcommand(const CLI::App* sub) const override {
    std::string name = "  " + sub->get_name();
    name.resize(std::max<std::size_t>(name.size() + 1, 16), ' ');
    return name + command_summary(sub->get_description(), kHelpWidth - name.size()) + "\n";
  }

  std::string make_footer(const CLI::App* app) const override {
    std::string footer = CLI::Formatter::make_footer(app);
    if (!app->get_parent())
      footer += (footer.empty() ? "" : "\n") +
                std::string("Each command's options and details: renderaudit COMMAND --help (or "
                            "renderaudit help COMMAND).\n");
    return footer;
  }

  std::string make_option_usage(const CLI::Option* o) const override {
    std::string name = o->get_name(true, false);
    if (o->get_expected_max() == CLI::detail::expected_max_vector_size) return name + " ...";
    std::string out = name;
    for (int i = 1; i < o->get_expected_min(); ++i) out += " " + name;
    return out;
  }

  std::string make_option_opts(const CLI::Option* o) const override {
    if (!o->get_option_text().empty()) return " " + o->get_option_text();
    if (o->get_type_size() == 0 || o->get_type_name().empty()) return "";  // a flag
    const std::string value = placeholder(o);
    std::string out = " " + value;
    if (o->get_expected_max() == CLI::detail::expected_max_vector_size)
      out += " ...";
    else
      for (int i = 1; i < o->get_expected_min(); ++i) out += " " + value;
    return out;
  }

  std::string make_option_desc(const CLI::Option* o) const override {
    std::string d = o->get_description();
    // One way of saying a default: "(default X)".
    for (std::size_t at; (at = d.find("default: ")) != std::string::npos;) d.erase(at + 7, 1);
    if (const std::size_t at = d.rfind(", default "); at != std::string::npos &&
                                                      d.find_first_of("()", at) == std::string::npos)
      d = d.substr(0, at) + " (default " + d.substr(at + 10) + ")";
    const std::string def = o->get_default_str();
    if (!def.empty() && d.find("default") == std::string::npos) d += " (default " + def + ")";
    if (o->get_required() && !o->get_positional()) d += " (required)";
    return d;
  }

  std::string make_option(const CLI::Option* o, bool positional) const override {
    std::string left = "  " + make_option_name(o, positional) + (positional ? "" : make_option_opts(o));
    const std::size_t col = get_column_width();
    std::string out;
    if (left.size() + 2 > col) {
      out = left + "\n";
      left.clear();
    }
    left.resize(col, ' ');
    const std::string desc = wrap_text(collapse_spaces(make_option_desc(o)), kHelpWidth - col);
    std::istringstream lines(desc);
    std::string line;
    for (bool first = true; std::getline(lines, line); first = false)
      out += (first ? left : std::string(col, ' ')) + line + "\n";
    if (desc.empty()) out += left + "\n";
    return out;
  }

 private:
  // `--jobs N`, `--threshold X`, `--out DIR`, `--db FILE`, `--kind {point,line,triangle}`.
  static std::string placeholder(const CLI::Option* o) {
    const std::string type = o->get_type_name();
    const std::string base = type.substr(0, type.find(':'));
    if (type.find(":{") != std::string::npos) return type.substr(type.find(":{") + 1);
    if (base == "INT" || base == "UINT") return "N";
    if (base == "FLOAT") return "X";
    static const std::map<std::string, std::string> paths = {
        {"out", "DIR"},        {"source", "DIR"},   {"cache", "DIR"},  {"state", "DIR"},
        {"baseline", "DIR"},   {"db", "FILE"},      {"experiment", "FILE"},
        {"expectations", "FILE"}, {"markdown", "FILE"}, {"upgrade-sentences", "FILE"},
        {"program", "FILE"},   {"llvm-config", "FILE"}};
    const auto it = paths.find(o->get_single_name());
    if (it != paths.end()) return it->second;
    return base == "TEXT" || base.empty() ? "TEXT" : base;
  }
};

void set_formatter(CLI::App& app, const std::shared_ptr<HelpFormatter>& f) {
  app.formatter(f);
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) set_formatter(*sub, f);
}

}  // namespace

void use_help_format(CLI::App& app) { set_formatter(app, std::make_shared<HelpFormatter>()); }

}  // namespace ra::app
