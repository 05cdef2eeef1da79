// The lean build's stand-ins (renderaudit-lean, for GPU and cluster nodes: docs/operations.md). It
// links no figure library (VTK, OpenImageIO, cairo, poppler), so the commands that draw figures or
// images, and the studies, are not in it: each is still listed, and says where it runs instead.
// The full build compiles the real commands in their place (CMakeLists.txt, RA_LEAN_ONLY_SOURCES).
#include <string>

#include "app/commands.h"
#include "rundir/study_dir.h"
#include "util/errors.h"

namespace ra::app {
namespace {

constexpr const char* kLeanBuild =
    "this is the lean build of renderaudit (no VTK, OpenImageIO, cairo or poppler: for GPU and "
    "cluster nodes)";

// A command of the full build: listed with what it does, refused with where to run it.
void register_full_build_command(CLI::App& app, const std::string& name, const std::string& what,
                                 const std::string& instead) {
  auto* cmd = app.add_subcommand(name, what + " (full build only: not in this lean build)");
  cmd->allow_extras();
  cmd->callback([name, instead] {
    throw util::UserError("`" + name + "`: " + kLeanBuild + "; " + instead);
  });
}

const std::string kCopyTheRun =
    "copy the run directory to a machine with the full build (`make` there) and run it there";

}  // namespace

void register_plot_command(CLI::App& app, int&) {
  register_full_build_command(app, "plot", "Draw every figure of a run (VTK)",
                              kCopyTheRun + ": renderaudit plot DIR");
}

void register_report_command(CLI::App& app, int&) {
  register_full_build_command(app, "report", "The run's report as PDF and HTML (cairo, poppler)",
                              kCopyTheRun + ": renderaudit report DIR");
}

void register_show_command(CLI::App& app, int&) {
  register_full_build_command(
      app, "show", "One primitive as a PNG (OpenImageIO)",
      "`renderaudit reproduce DIR ...` writes the same primitive as a C program for this node");
}

void register_history_command(CLI::App& app, int&) {
  register_full_build_command(app, "history", "The audit history and its trend figures (VTK)",
                              "copy the history database to a machine with the full build");
}

void register_timing_command(CLI::App& app, int&) {
  register_full_build_command(app, "timing", "The rendering-time study",
                              "the studies draw figures: run them with the full build");
}

void register_bisect_command(CLI::App& app, int&) {
  register_full_build_command(app, "bisect", "The driver commit of a change",
                              "its report draws images of the changed primitives: run it with "
                              "the full build");
}

void register_watch_command(CLI::App& app, int&) {
  register_full_build_command(app, "watch", "A night following a Mesa branch",
                              "its bisections draw images of the changed primitives: run it with "
                              "the full build");
}

bool run_study_if_declared(const rundir::StudyRunOptions& options, int&) {
  const rundir::StudyKind kind = rundir::experiment_study_kind(options.experiment);
  if (kind == rundir::StudyKind::kAudit) return false;
  throw util::UserError(options.experiment + " declares the " + rundir::study_kind_name(kind) +
                        " study; " + kLeanBuild + ", which runs primitive audits only: run the "
                        "study with the full build");
}

bool analyze_study_if_present(const std::string& dir, int&) {
  const std::optional<rundir::StudyInfo> info = rundir::read_study_info(dir);
  if (!info || info->kind == rundir::StudyKind::kAudit) return false;
  throw util::UserError(dir + " is a " + rundir::study_kind_name(info->kind) + " study folder; " +
                        kLeanBuild + ": analyse it with the full build");
}

}  // namespace ra::app
