// Which study an experiment file declares, and the study.json that marks a study's output folder.
//
// An experiment file's top-level tables say what `renderaudit run` does with it:
//   [timing]      the rendering-time study (timing/),
//   [lod]         the terrain level-of-detail study (terrain_lod/),
//   [regulation]  the decision-theoretic regulation study (regulation/),
//   none of them  the primitive audit (rundir/experiment.h: [[platforms]], [views], ...).
// A study folder holds study.json, written when its `run` completes and rewritten by `analyze`:
//   {"schema": 1, "kind": "lod", "name": "...", "title": "...", "subtitle": "...",
//    "document": "lod.md", "analysed": true}
// `document` is the folder's markdown text for the report (empty until `analyze` has run);
// `renderaudit report DIR` turns it and DIR/figures/index.json into report.pdf and report.html.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace ra::rundir {

enum class StudyKind { kAudit, kTiming, kLod, kRegulation };

const char* study_kind_name(StudyKind kind);  // "audit", "timing", "lod", "regulation"

// The kind an experiment file declares. Throws UserError (file:line:column) for a TOML syntax
// error or a file that declares two studies at once.
StudyKind experiment_study_kind(const std::string& experiment_path);

struct StudyInfo {
  StudyKind kind = StudyKind::kAudit;
  std::string name;      // the experiment's name
  std::string title;     // the report's title
  std::string subtitle;  // one paragraph under it
  std::string document;  // markdown file inside the folder; empty before `analyze`
  bool analysed = false;
};

// DIR/study.json, written atomically.
void write_study_info(const std::string& dir, const StudyInfo& info);
// DIR/study.json when there is one; throws UserError when it exists but cannot be read.
std::optional<StudyInfo> read_study_info(const std::string& dir);

// What `renderaudit run` hands a study, and what the study hands back. Each study provides
//   StudyRunResult run_<kind>_study(const StudyRunOptions&);   measures, writes study.json last
//   void analyze_<kind>_study(const std::string& dir);        tables, DIR/<kind>.md, study.json
//   void plot_<kind>_study(const std::string& dir);           DIR/figures/ (plots/figure_set.h)
struct StudyRunOptions {
  std::string experiment;              // the experiment file
  std::string out_dir;                 // empty: outputs/<experiment name>
  std::vector<std::string> platforms;  // --platform filters; empty: all of the file's
  bool progress = true;                // progress lines on stderr
};

struct StudyRunResult {
  std::string dir;       // the study folder written
  std::string summary;   // a few lines for the terminal
  bool findings = false; // a check failed (exit code 1): the summary says which
};

}  // namespace ra::rundir
