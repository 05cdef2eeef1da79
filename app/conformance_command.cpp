// `renderaudit conformance RUN [--expectations FILE] [--junit FILE] [--write-expectations FILE]`:
// a run's violations of the rasterization rules as a CI verdict
// (analysis/conformance_expectations.h): an exit code, JUnit XML, and an expectations file of the
// known violations, written from a run and then honoured. `run` and `report` take
// --fail-on-violations and --expectations for the same verdict at their end
// (add_conformance_gate_options).
#include <cstdio>

#include "analysis/conformance_expectations.h"
#include "analysis/run_completeness.h"
#include "app/commands.h"
#include "util/atomic_file.h"
#include "util/errors.h"

namespace ra::app {
namespace {

struct ConformanceOptions {
  std::string run_dir, expectations, junit, write_expectations;
  bool fail_on_fixed = false;
  bool allow_incomplete = false;
};

}  // namespace

void add_conformance_gate_options(CLI::App* cmd, ConformanceGate& gate) {
  cmd->add_flag("--fail-on-violations", gate.fail_on_violations,
                "end with exit code 5 when the run breaks a rasterization rule (docs/conformance.md"
                "#conformance-in-ci); `renderaudit conformance` says more");
  cmd->add_option("--expectations", gate.expectations,
                  "with --fail-on-violations: the violations this file lists are known and pass; "
                  "only others give exit code 5")
      ->check(CLI::ExistingFile);
}

void read_conformance_gate(ConformanceGate& gate) {
  if (!gate.expectations.empty()) {
    gate.fail_on_violations = true;
    gate.parsed =
        std::make_shared<analysis::Expectations>(analysis::read_expectations(gate.expectations));
  }
}

int conformance_gate_exit(const ConformanceGate& gate, const std::string& run_dir, int exit_code) {
  if (!gate.fail_on_violations) return exit_code;
  const analysis::ConformanceCheck c = analysis::check_conformance(run_dir, gate.parsed.get());
  std::printf("%s", analysis::conformance_text(c).c_str());
  return exit_code == kExitOk && c.new_violations() ? kExitViolations : exit_code;
}

void register_conformance_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "conformance",
      "A run's violations of the rasterization rules as a CI verdict: exit 0 when every\n"
      "violation is known (listed in --expectations FILE; without it, when there is none), exit 5\n"
      "when any other is found. --junit FILE: JUnit XML, one test case per platform x kind x\n"
      "view. --write-expectations FILE: the run's violations as that file, one primitive per\n"
      "line (PLATFORM KIND VIEW INDEX), to review and commit beside the driver. A listed\n"
      "primitive drawn without violation now is reported as fixed (--fail-on-fixed: exit 5 too).\n"
      "Format and use in CI: docs/conformance.md.");
  const auto o = std::make_shared<ConformanceOptions>();  // alive as long as the callbacks
  cmd->add_option("run", o->run_dir, "run directory")->required()->check(CLI::ExistingDirectory);
  cmd->add_option("--expectations", o->expectations,
                  "the known violations (plain text, PLATFORM KIND VIEW INDEX per line)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--junit", o->junit,
                  "write JUnit XML there (a test case per platform x kind "
                  "x view)");
  cmd->add_option("--write-expectations", o->write_expectations,
                  "write the run's violations there as an expectations file");
  cmd->add_flag("--fail-on-fixed", o->fail_on_fixed,
                "exit 5 also when a listed primitive is no longer a violation, so that the list "
                "is kept exact (deqp-runner's UnexpectedImprovement)");
  cmd->add_flag("--allow-incomplete", o->allow_incomplete,
                "judge a run with missing or damaged shards (said); without it such a run is "
                "refused with exit code 3");
  cmd->callback([o, &exit_code] {
    // The expectations are read first: a malformed file stops before anything is read or written.
    std::unique_ptr<analysis::Expectations> expected;
    if (!o->expectations.empty())
      expected =
          std::make_unique<analysis::Expectations>(analysis::read_expectations(o->expectations));
    const analysis::RunCompleteness whole = analysis::check_run_completeness(o->run_dir);
    if (!whole.complete()) {
      if (!o->allow_incomplete) {
        std::fprintf(stderr, "renderaudit conformance: %s: %s\n%s\n", o->run_dir.c_str(),
                     whole.one_line().c_str(), whole.remedy("conformance").c_str());
        exit_code = kExitIncomplete;
        return;
      }
      std::fprintf(stderr, "renderaudit conformance: %s: %s\n", o->run_dir.c_str(),
                   whole.one_line().c_str());
    }
    const analysis::ConformanceCheck c = analysis::check_conformance(o->run_dir, expected.get());
    if (!o->junit.empty()) util::write_file_atomic(o->junit, analysis::conformance_junit(c));
    if (!o->write_expectations.empty())
      util::write_file_atomic(o->write_expectations, analysis::expectations_text(c));
    // Writing the list without one to judge by is the step that makes it: no verdict, exit 0.
    const bool judge = !o->expectations.empty() || o->write_expectations.empty();
    std::printf("%s", analysis::conformance_text(c, judge).c_str());
    if (!o->write_expectations.empty())
      std::printf("expectations: %zu violation%s written to %s\n", c.violations(),
                  c.violations() == 1 ? "" : "s", o->write_expectations.c_str());
    if (!o->junit.empty()) std::printf("junit: %s\n", o->junit.c_str());
    const bool fails = c.new_violations() || (o->fail_on_fixed && c.fixed());
    exit_code = judge && fails ? kExitViolations : kExitOk;
  });
}

}  // namespace ra::app
