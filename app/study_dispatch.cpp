// `run`, `analyze` and `plot` of the studies (rundir/study_dir.h): an experiment file with a
// [timing], [lod] or [regulation] table, and the folders those studies write. The audit's own
// commands call these first and go on with the primitive audit when they return false. What
// differs between the studies is behind the Study interface (study.h).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "app/commands.h"
#include "app/study.h"
#include "rundir/run_folder.h"
#include "rundir/study_dir.h"
#include "util/program_name.h"
#include "util/shell_quote.h"

namespace ra::app {

bool run_study_if_declared(const rundir::StudyRunOptions& options, int& exit_code) {
  const std::unique_ptr<Study> study = study_of(rundir::experiment_study_kind(options.experiment));
  if (!study) return false;
  const rundir::StudyRunResult r = study->run(options);
  std::printf("%s", r.summary.c_str());
  if (!r.summary.empty() && r.summary.back() != '\n') std::printf("\n");
  if (study->has_report())
    std::printf("next: renderaudit report %s (runs analyze and plot first)\n", r.dir.c_str());
  exit_code = r.findings ? kExitFindings : kExitOk;
  return true;
}

namespace {

// The study that wrote a folder; nullptr for an audit run or a folder of no study.
std::unique_ptr<Study> study_in(const std::string& dir) {
  const std::optional<rundir::StudyInfo> info = rundir::read_study_info(dir);
  return info ? study_of(info->kind) : nullptr;
}

}  // namespace

bool analyze_study_if_present(const std::string& dir, int& exit_code) {
  const std::unique_ptr<Study> study = study_in(dir);
  if (!study) return false;
  study->analyze(dir);
  const std::optional<rundir::StudyInfo> after = rundir::read_study_info(dir);
  if (after && !after->document.empty())
    std::printf("analysis: %s/%s\n", dir.c_str(), after->document.c_str());
  exit_code = kExitOk;
  return true;
}

bool plot_study_if_present(const std::string& dir, int& exit_code) {
  const std::unique_ptr<Study> study = study_in(dir);
  if (!study) return false;
  study->plot(dir);
  std::printf("figures: %s/figures/index.json\n", dir.c_str());
  exit_code = kExitOk;
  return true;
}

bool prepare_study_report(const std::string& dir, bool run_missing) {
  const std::optional<rundir::StudyInfo> info = rundir::read_study_info(dir);
  const std::unique_ptr<Study> study = info ? study_of(info->kind) : nullptr;
  if (!study || !study->has_report()) return false;
  const bool analysed = info->analysed && !info->document.empty();
  const bool plotted = std::filesystem::exists(rundir::run_folder::figure_index(dir));
  if (analysed && plotted) return false;
  if (!run_missing) return false;  // the report names the missing commands
  int ignored = 0;
  if (!analysed) {
    std::fprintf(stderr, "report: running `%s analyze %s`\n", util::program_for_commands().c_str(),
                 util::shell_quote(dir).c_str());
    analyze_study_if_present(dir, ignored);
  }
  if (!analysed || !plotted) {
    std::fprintf(stderr, "report: running `%s plot %s`\n", util::program_for_commands().c_str(),
                 util::shell_quote(dir).c_str());
    plot_study_if_present(dir, ignored);
  }
  return true;
}

}  // namespace ra::app
