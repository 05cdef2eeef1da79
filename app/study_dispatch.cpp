// `run`, `analyze` and `plot` of the studies (rundir/study_dir.h): an experiment file with a
// [timing], [lod] or [regulation] table, and the folders those studies write. The audit's own
// commands call these first and go on with the primitive audit when they return false.
#include <cstdio>
#include <filesystem>
#include <optional>

#include "app/commands.h"
#include "regulation/regulation_study.h"
#include "util/errors.h"
#include "rundir/study_dir.h"
#include "terrain_lod/lod_study.h"
#include "timing/timing_run.h"

namespace ra::app {

bool run_study_if_declared(const rundir::StudyRunOptions& options, int& exit_code) {
  const rundir::StudyKind kind = rundir::experiment_study_kind(options.experiment);
  rundir::StudyRunResult r;
  switch (kind) {
    case rundir::StudyKind::kAudit:
      return false;
    case rundir::StudyKind::kTiming:
      r = timing::run_timing_study(options);
      break;
    case rundir::StudyKind::kLod:
      r = lod::run_lod_study(options);
      break;
    case rundir::StudyKind::kRegulation:
      r = regulation::run_regulation_study(options);
      break;
  }
  std::printf("%s", r.summary.c_str());
  if (!r.summary.empty() && r.summary.back() != '\n') std::printf("\n");
  if (kind != rundir::StudyKind::kTiming)
    std::printf("next: renderaudit report %s (runs analyze and plot first)\n", r.dir.c_str());
  exit_code = r.findings ? kExitFindings : kExitOk;
  return true;
}

bool analyze_study_if_present(const std::string& dir, int& exit_code) {
  const std::optional<rundir::StudyInfo> info = rundir::read_study_info(dir);
  if (!info || info->kind == rundir::StudyKind::kAudit) return false;
  switch (info->kind) {
    case rundir::StudyKind::kTiming:
      std::printf("%s: a timing study is analysed as it runs (%s/timing.md); nothing to do\n",
                  dir.c_str(), dir.c_str());
      break;
    case rundir::StudyKind::kLod:
      lod::analyze_lod_study(dir);
      break;
    case rundir::StudyKind::kRegulation:
      regulation::analyze_regulation_study(dir);
      break;
    case rundir::StudyKind::kAudit:
      break;
  }
  const std::optional<rundir::StudyInfo> after = rundir::read_study_info(dir);
  if (after && !after->document.empty())
    std::printf("analysis: %s/%s\n", dir.c_str(), after->document.c_str());
  exit_code = kExitOk;
  return true;
}

bool plot_study_if_present(const std::string& dir, int& exit_code) {
  const std::optional<rundir::StudyInfo> info = rundir::read_study_info(dir);
  if (!info || info->kind == rundir::StudyKind::kAudit) return false;
  switch (info->kind) {
    case rundir::StudyKind::kTiming:
      std::printf("%s: a timing study draws its figures as it runs (%s/figures/); nothing to do\n",
                  dir.c_str(), dir.c_str());
      break;
    case rundir::StudyKind::kLod:
      lod::plot_lod_study(dir);
      break;
    case rundir::StudyKind::kRegulation:
      regulation::plot_regulation_study(dir);
      break;
    case rundir::StudyKind::kAudit:
      break;
  }
  std::printf("figures: %s/figures/index.json\n", dir.c_str());
  exit_code = kExitOk;
  return true;
}

bool prepare_study_report(const std::string& dir, bool run_missing) {
  const std::optional<rundir::StudyInfo> info = rundir::read_study_info(dir);
  if (!info || info->kind == rundir::StudyKind::kAudit || info->kind == rundir::StudyKind::kTiming)
    return false;
  const bool analysed = info->analysed && !info->document.empty();
  const bool plotted = std::filesystem::exists(dir + "/figures/index.json");
  if (analysed && plotted) return false;
  if (!run_missing) return false;  // the report names the missing commands
  int ignored = 0;
  if (!analysed) {
    std::fprintf(stderr, "report: running `renderaudit analyze %s`\n", dir.c_str());
    analyze_study_if_present(dir, ignored);
  }
  if (!analysed || !plotted) {
    std::fprintf(stderr, "report: running `renderaudit plot %s`\n", dir.c_str());
    plot_study_if_present(dir, ignored);
  }
  return true;
}

}  // namespace ra::app
