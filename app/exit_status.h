// How a command that stopped on an exception ends: one mapping for renderaudit and
// renderaudit-worker (app/main.cpp, app/worker_main.cpp).
#pragma once

#include <CLI/CLI.hpp>

namespace ra::app {

// Parses the command line into `app` and runs the chosen subcommand (which sets `exit_code`), then
// returns the process's exit code: `exit_code`; 0 for --help and --version; kExitUsage for a
// command line CLI11 rejects; exit_code_of_current_exception(program) when the command throws.
int run_command_line(CLI::App& app, int argc, char** argv, const int& exit_code,
                     const char* program);

// Call inside a catch block of main: says the exception being handled on stderr ("PROGRAM: WHAT"
// for bad input, util::UserError; "PROGRAM: error: WHAT" for any other) and to a parent renderaudit
// process, and returns the exit code: kExitError (2) whatever the exception. An I/O failure (a full
// disk) or a library's error is an error like bad input, never kExitFindings, which says the
// command ran and found something (failed shards, a changed verdict). The one exception that is
// not an error: util::StdoutReaderGone, a reader of standard output that stopped early (`| head`),
// ends the command quietly with kExitOk, as `cat` ends when its reader is gone.
int exit_code_of_current_exception(const char* program);

// Call when the command has ended with `exit_code`: checks what it wrote to standard output
// (util/standard_output.h). Written, or its reader gone (quietly): `exit_code`. Any other failed
// write (a full disk): says "PROGRAM: cannot write to standard output (WHY)" and returns
// kExitError: a command whose output was lost did not do what it was asked.
int exit_code_after_stdout(int exit_code, const char* program);

}  // namespace ra::app
