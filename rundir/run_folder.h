// The names of a run directory's files and folders, written once: every command that reads or
// writes a run builds its paths here, never by spelling a name (scripts/check_layout.py fails on
// a run folder's file name spelled as a path outside rundir/). Each function takes the run
// directory DIR (or, where a command lets --out move a folder, that folder) and returns
// DIR + "/" + the name. What each file holds is documented where it is written and read.
#pragma once

#include <cstdint>
#include <string>

namespace ra::rundir::run_folder {

using Dir = const std::string&;

std::string experiment(Dir dir);   // experiment.toml: the experiment as run, copied in
std::string manifest(Dir dir);     // manifest.json: the run's provenance (manifest.h)
std::string records(Dir dir);      // records/: one sealed records file per shard (shard_file.h)
std::string drivers(Dir dir);      // drivers/: one PLATFORM.json per platform
std::string driver(Dir dir, const std::string& platform);  // drivers/PLATFORM.json: its GL strings
std::string logs(Dir dir);         // logs/: one log per shard a worker drew
// logs/SHARD.log, or SHARD.retry.log for a second attempt: the worker's output for the shard
std::string shard_log(Dir dir, const std::string& shard, bool retry = false);
std::string parts(Dir dir);        // parts/: the halves of a shard cut to find a crash
std::string slices(Dir dir);       // slices/: a Slurm submission's slice folders
std::string slurm(Dir dir);        // slurm/: a Slurm submission's scripts, logs and exit status
std::string slurm_jobs(Dir dir);   // slurm/jobs.json: a Slurm submission's jobs
std::string progress(Dir dir);     // progress.json: a running run's counts (runner/run_progress.h)
std::string summary(Dir dir);      // summary.md: the summary `run` and `merge` print, kept
std::string study(Dir dir);        // study.json: marks a study folder (study_dir.h)
std::string timing(Dir dir);       // timing.json: the timing study's numbers

std::string analysis(Dir dir);     // analysis/: what `analyze` writes
std::string tally(Dir dir);        // analysis/tally.json: the counts (analysis/run_tally.h)
std::string figure_data(Dir dir);  // analysis/figures.json: the figures' numbers
std::string figures(Dir dir);      // figures/: what `plot` draws
std::string figure_index(Dir dir); // figures/index.json: the figures drawn (plots/plot_run.h)
std::string report(Dir dir);       // report/: what `report` writes
std::string report_pdf(Dir dir);   // report/report.pdf
std::string report_html(Dir dir);  // report/report.html
std::string audit(Dir dir);        // audit/: `audit`'s default --out
std::string reproduce(Dir dir);    // reproduce/: `reproduce`'s default folder for its C files
// reproduce/PLATFORM.KIND.vVIEW.INDEX.c: `reproduce`'s C file of one record by default
std::string reproducer_source(Dir dir, const std::string& platform, const std::string& kind,
                              int view, std::uint64_t index);
// audit-NAME/: an audit of NAME ("P" or "P-source": the driver upgrade's, scripts/driver-upgrade.sh;
// "P" in a night of `watch`, STATE/nights/N)
std::string named_audit(Dir dir, const std::string& name);
// audit-A-vs-B/: `audit DIR --between A B`'s default --out
std::string audit_between(Dir dir, const std::string& a, const std::string& b);
// bisect-P/: the bisection of platform P in a night of `watch`
std::string named_bisect(Dir dir, const std::string& name);
std::string audit_json(Dir audit_dir);  // AUDIT/audit.json: the verdict, everything (audit/)
std::string audit_md(Dir audit_dir);    // AUDIT/audit.md: the verdict to read
// upgrade-summary-BUILD.json: the driver upgrade's counts against BUILD (report/upgrade_summary.h)
std::string upgrade_summary(Dir dir, const std::string& build);
std::string upgrade_pictures(Dir dir);  // upgrade-pictures/: its pictures and C reproducers
std::string bisect(Dir dir);       // bisect/: `bisect`'s default --out
std::string bisection(Dir bisect_dir);     // OUT/bisect.json: the bisection's state and result
std::string bisection_md(Dir bisect_dir);  // OUT/bisect.md: its report

// The bare names, for the writers that list a folder's files rather than build a path.
inline constexpr const char* kExperimentFile = "experiment.toml";
inline constexpr const char* kManifestFile = "manifest.json";
inline constexpr const char* kTallyFile = "tally.json";
inline constexpr const char* kFigureDataFile = "figures.json";
inline constexpr const char* kAuditJsonFile = "audit.json";
inline constexpr const char* kAuditMdFile = "audit.md";
inline constexpr const char* kAuditJunitFile = "junit.xml";
inline constexpr const char* kTimingFile = "timing.json";

}  // namespace ra::rundir::run_folder
