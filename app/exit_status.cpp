// The exit code of a command stopped by an exception (see the header).
#include "app/exit_status.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstring>
#include <exception>

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

int run_command_line(CLI::App& app, int argc, char** argv, const int& exit_code,
                     const char* program) {
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
