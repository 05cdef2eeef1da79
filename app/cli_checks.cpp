// Checks of command-line values shared by several commands (app/commands.h).
#include <algorithm>
#include <cerrno>
#include <cstdlib>

#include "app/commands.h"

namespace ra::app {

CLI::Validator primitive_index_check() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const bool digits =
            !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
        errno = 0;
        if (digits) std::strtoull(text.c_str(), nullptr, 10);
        if (!digits || errno == ERANGE)
          return "--index " + text + ": not a primitive index (allowed: a whole number from "
                 "0 to 18446744073709551615, below the experiment's count)";
        return "";
      },
      "INDEX");
}

void add_primitive_options(CLI::App* cmd, const PrimitiveOptions& into,
                           const std::string& platform_help) {
  cmd->add_option("run", into.run_dir, "run directory (holds experiment.toml)")->required();
  cmd->add_option("--platform,-p", into.platform, platform_help)->required();
  cmd->add_option("--kind,-k", into.kind, "point, line or triangle")->required();
  cmd->add_option("--view,-v", into.view, "view number, 1-based (Table 1 order)")->required();
  cmd->add_option("--index,-i", into.index, "primitive index under the run's seed")
      ->required()
      ->check(primitive_index_check());
}

}  // namespace ra::app
