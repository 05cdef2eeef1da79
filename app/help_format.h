// How every `--help` of renderaudit reads: lines of at most 100 columns, one convention for
// options (`--jobs N`, `--out DIR`: a placeholder, never CLI11's type and check such as
// `UINT:INT in [1 - 1000000]=2000`; a default said once, in words, "(default 2000)"), and a short
// top help with one line per command, its details in `renderaudit COMMAND --help`.
#pragma once

#include <CLI/CLI.hpp>
#include <cstddef>
#include <string>

namespace ra::app {

constexpr std::size_t kHelpWidth = 100;

// `text` with every line longer than `width` broken at spaces, later lines of a broken one
// indented by `indent`; the text's own line breaks are kept.
std::string wrap_text(const std::string& text, std::size_t width, std::size_t indent = 0);

// A command's one-line summary for the top help: the first sentence of its description, cut at
// its first colon, then without parentheses, then at a comma, until it fits `width`.
std::string command_summary(const std::string& description, std::size_t width);

// Gives `app` and all its subcommands the formatter, and the top help its footer.
void use_help_format(CLI::App& app);

}  // namespace ra::app
