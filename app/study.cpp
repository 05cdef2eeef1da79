// The three studies behind the Study interface (study.h): each forwards to its folder's run,
// analyze and plot functions.
#include "app/study.h"

#include <cstdio>

#include "regulation/regulation_document.h"
#include "regulation/regulation_figures.h"
#include "regulation/regulation_run.h"
#include "terrain_lod/lod_document.h"
#include "terrain_lod/lod_figures.h"
#include "terrain_lod/lod_run.h"
#include "timing/timing_run.h"

namespace ra::app {
namespace {

class TimingStudy : public Study {
 public:
  rundir::StudyRunResult run(const rundir::StudyRunOptions& options) const override {
    return timing::run_timing_study(options);
  }
  void analyze(const std::string& dir) const override {
    std::printf("%s: a timing study is analysed as it runs (%s/timing.md); nothing to do\n",
                dir.c_str(), dir.c_str());
  }
  void plot(const std::string& dir) const override {
    std::printf("%s: a timing study draws its figures as it runs (%s/figures/); nothing to do\n",
                dir.c_str(), dir.c_str());
  }
  bool has_report() const override { return false; }
};

class LodStudy : public Study {
 public:
  rundir::StudyRunResult run(const rundir::StudyRunOptions& options) const override {
    return lod::run_lod_study(options);
  }
  void analyze(const std::string& dir) const override { lod::analyze_lod_study(dir); }
  void plot(const std::string& dir) const override { lod::plot_lod_study(dir); }
  bool has_report() const override { return true; }
};

class RegulationStudy : public Study {
 public:
  rundir::StudyRunResult run(const rundir::StudyRunOptions& options) const override {
    return regulation::run_regulation_study(options);
  }
  void analyze(const std::string& dir) const override {
    regulation::analyze_regulation_study(dir);
  }
  void plot(const std::string& dir) const override { regulation::plot_regulation_study(dir); }
  bool has_report() const override { return true; }
};

}  // namespace

std::unique_ptr<Study> study_of(rundir::StudyKind kind) {
  switch (kind) {
    case rundir::StudyKind::kAudit:
      return nullptr;
    case rundir::StudyKind::kTiming:
      return std::make_unique<TimingStudy>();
    case rundir::StudyKind::kLod:
      return std::make_unique<LodStudy>();
    case rundir::StudyKind::kRegulation:
      return std::make_unique<RegulationStudy>();
  }
  return nullptr;
}

}  // namespace ra::app
