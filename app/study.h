// A study the program runs besides the primitive audit (rundir/study_dir.h): timing, LOD or
// regulation. Each kind is one implementation of Study (app/study.cpp); study_dispatch.cpp asks
// study_of the kind an experiment file or study folder declares and never switches on it again.
#pragma once

#include <memory>
#include <string>

#include "rundir/study_dir.h"

namespace ra::app {

class Study {
 public:
  virtual ~Study() = default;
  // Runs the study an experiment file declares; its summary and folder.
  virtual rundir::StudyRunResult run(const rundir::StudyRunOptions& options) const = 0;
  // `analyze DIR` and `plot DIR` of a folder the study wrote.
  virtual void analyze(const std::string& dir) const = 0;
  virtual void plot(const std::string& dir) const = 0;
  // Whether `report DIR` builds a report from the analysis and figures (then `run` ends by
  // naming that command); the timing study writes its document and figures as it runs.
  virtual bool has_report() const = 0;
};

// The study of a kind; nullptr for the primitive audit (kAudit), which is no Study.
std::unique_ptr<Study> study_of(rundir::StudyKind kind);

}  // namespace ra::app
