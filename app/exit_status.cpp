// The exit code of a command stopped by an exception (see the header).
#include "app/exit_status.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "app/commands.h"
#include "util/child_process.h"
#include "util/errors.h"
#include "util/standard_output.h"

namespace ra::app {

int exit_code_of_current_exception(const char* program) {
  try {
    throw;
  } catch (const util::StdoutReaderGone&) {
    return kExitOk;
  } catch (const util::UserError& e) {
    util::send_message_to_parent(e.what());
    std::fprintf(stderr, "%s: %s\n", program, e.what());
  } catch (const std::exception& e) {
    util::send_message_to_parent(e.what());
    std::fprintf(stderr, "%s: error: %s\n", program, e.what());
  } catch (...) {
    util::send_message_to_parent("an exception of unknown type");
    std::fprintf(stderr, "%s: error: an exception of unknown type\n", program);
  }
  return kExitError;
}

int exit_code_after_stdout(int exit_code, const char* program) {
  const util::StdoutOutcome o = util::finish_stdout();
  if (o.state != util::StdoutState::kFailed) return exit_code;
  std::fprintf(stderr, "%s: cannot write to standard output (%s)\n", program,
               o.error ? std::strerror(o.error) : "a write failed: is the disk full?");
  return kExitError;
}

namespace {

// The long option names of `cmd` and of the commands under it.
void long_names(const CLI::App* cmd, std::vector<std::string>& names) {
  for (const CLI::Option* o : cmd->get_options())
    for (const std::string& l : o->get_lnames()) names.push_back("--" + l);
  for (const CLI::App* sub : cmd->get_subcommands([](const CLI::App*) { return true; }))
    long_names(sub, names);
}

// "renderaudit run: unknown option '--ouT'; did you mean '--out'? (...)", exit 2.
int unknown_option(const std::string& command, const std::string& option,
                   const std::vector<std::string>& names) {
  const std::string near = nearest_name(option, names);
  std::fprintf(stderr, "%s: unknown option '%s'%s (%s --help lists them)\n", command.c_str(),
               option.c_str(), near.empty() ? "" : ("; did you mean '" + near + "'?").c_str(),
               command.c_str());
  return kExitUsage;
}

}  // namespace

int run_command_line(CLI::App& app, int argc, char** argv, const int& exit_code,
                     const char* program) {
  // A mistyped option (`--ouT`, `--speed-repeat 3`) is named with the nearest option of its
  // command before CLI11 parses: CLI11 would read some as values of a positional and complain of
  // those instead.
  if (argc > 1) {
    const CLI::App* cmd = nullptr;
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
      if (sub->get_name() == argv[1]) cmd = sub;
    if (cmd) {
      std::vector<std::string> names = {"--help"};
      long_names(cmd, names);
      for (int i = 2; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--") break;  // what follows is not options (bisect's paths)
        if (arg.rfind("--", 0) != 0) continue;
        const std::string option = arg.substr(0, arg.find('='));
        if (std::find(names.begin(), names.end(), option) == names.end())
          return unknown_option(std::string(program) + " " + cmd->get_name(), option, names);
      }
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : kExitUsage;
  } catch (...) {
    return exit_code_of_current_exception(program);
  }
  return exit_code;
}

}  // namespace ra::app
