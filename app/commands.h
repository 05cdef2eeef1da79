// The subcommands of the `renderaudit` program. Each registers itself on the CLI11 app; its
// callback throws ra::util::UserError for bad input and sets the process exit code through `exit_code`.
// Option values: each command keeps them in a struct of its own, made at registration and held
// through a shared_ptr by the callbacks that read them; no static state, so the commands can be
// registered again in one process (the tests do).
// The lean program (renderaudit-lean) defines plot, report, show, history, timing, bisect and the
// study functions below as stand-ins that name the full build (app/lean_build.cpp).
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "analysis/conformance_expectations.h"
#include "rundir/study_dir.h"
#include "builds/source_build.h"
#include "triage/bisect_speed.h"
#include "util/nearest_name.h"

namespace ra::app {

// Exit codes shared by all subcommands.
constexpr int kExitOk = 0;
constexpr int kExitFindings = 1;  // the command ran, and what it found is not clean (failed shards)
constexpr int kExitUsage = 2;     // bad input: nothing was run
// an error stopped the command: bad input, or an I/O failure (a full disk); never kExitFindings
// (app/exit_status.h). A reader of stdout that stopped early is no error: the command's own code.
constexpr int kExitError = kExitUsage;
constexpr int kExitIncomplete = 3;  // analyze / report: the run is not whole (missing or damaged
                                    // shards, a writer at work); nothing written
                                    // (--allow-incomplete goes on)
// conformance, and run / report with --fail-on-violations: the run breaks a rasterization rule
// in a primitive the expectations do not list. Its own code, so that a CI job tells a driver
// that breaks GL's rules from a run that failed (1) or could not start (2); 4 is status's.
constexpr int kExitViolations = 5;

// --index checked as text: a conversion to an unsigned number would turn -1, and any number past
// the largest, into 18446744073709551615 (app/cli_checks.cpp).
CLI::Validator primitive_index_check();

// The options that name one primitive of a run, as `reproduce` and `show` take them: RUN,
// --platform (its help given: what the platform is for), --kind, --view and --index, all required.
struct PrimitiveOptions {
  std::string& run_dir;
  std::string& platform;
  std::string& kind;
  int& view;
  uint64_t& index;
};
void add_primitive_options(CLI::App* cmd, const PrimitiveOptions& into,
                           const std::string& platform_help);

using util::nearest_name;  // util/nearest_name.h

void register_run_command(CLI::App& app, int& exit_code);
void register_worker_command(CLI::App& app, int& exit_code);  // internal: one shard, one process
void register_stats_command(CLI::App& app, int& exit_code);
void register_analyze_command(CLI::App& app, int& exit_code);
void register_plot_command(CLI::App& app, int& exit_code);    // figures: PNG + PDF (plots/)
void register_report_command(CLI::App& app, int& exit_code);  // report.pdf + report.html (report/)
void register_audit_command(CLI::App& app, int& exit_code);    // run vs baseline: verdict (audit/)
void register_history_command(CLI::App& app, int& exit_code);  // audit history + trend figures
void register_show_command(CLI::App& app, int& exit_code);     // one primitive as a PNG
void register_timing_command(CLI::App& app, int& exit_code);   // rendering-time study (timing/)
void register_platforms_command(CLI::App& app, int& exit_code);  // what this machine can draw with
void register_merge_command(CLI::App& app, int& exit_code);      // slices of a run gathered
void register_status_command(CLI::App& app, int& exit_code);
void register_records_command(CLI::App& app, int& exit_code);  // a run's records as one stream
void register_builds_command(CLI::App& app, int& exit_code);
void register_reproduce_command(CLI::App& app, int& exit_code);  // one record as a C program
void register_bisect_command(CLI::App& app, int& exit_code);     // the driver commit of a change
void register_watch_command(CLI::App& app, int& exit_code);      // a night following a Mesa branch
void register_conformance_command(CLI::App& app, int& exit_code);  // violations as a CI verdict

// `run` and `report` --fail-on-violations [--expectations FILE] (app/conformance_command.cpp):
// the verdict of `renderaudit conformance` at their end. read_conformance_gate reads the file
// before any work (a malformed one stops the command first); conformance_gate_exit prints the
// verdict and returns kExitViolations when `exit_code` is kExitOk and a violation is not listed,
// else `exit_code` (a failed run keeps its own code).
struct ConformanceGate {
  bool fail_on_violations = false;
  std::string expectations;
  std::shared_ptr<analysis::Expectations> parsed;
};
void add_conformance_gate_options(CLI::App* cmd, ConformanceGate& gate);
void read_conformance_gate(ConformanceGate& gate);
int conformance_gate_exit(const ConformanceGate& gate, const std::string& run_dir, int exit_code);

// The options of building many commits of a Mesa tree (`bisect`, `watch`): --cache,
// --llvm-config, -D, --build-command and --fresh-builds (set in `fresh_builds`).
void add_commit_build_options(CLI::App* cmd, builds::SourceBuildOptions& build, bool& fresh_builds);
// --speed, --speed-repeats, --speed-primitives, --speed-threshold of `bisect` and `watch`
// (`what` says what --speed does there); check_speed_options refuses the last three without
// --speed.
void add_speed_attribution_options(CLI::App* cmd, triage::BisectSpeedOptions& speed,
                                   const std::string& what);
void check_speed_options(const std::string& command, const triage::BisectSpeedOptions& speed);

// The studies (app/study_dispatch.cpp): each returns false when its argument is not a study (an
// audit experiment or run folder), and otherwise does the study's stage and sets exit_code.
bool run_study_if_declared(const rundir::StudyRunOptions& options, int& exit_code);
bool analyze_study_if_present(const std::string& dir, int& exit_code);
bool plot_study_if_present(const std::string& dir, int& exit_code);
// Before `report` on a LOD or regulation folder: runs its analyze and plot stages when their
// outputs are missing and `run_missing`. True when it ran something.
bool prepare_study_report(const std::string& dir, bool run_missing);

}  // namespace ra::app
