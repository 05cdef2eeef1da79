// The names of a run directory's files and folders (see the header).
#include "rundir/run_folder.h"

namespace ra::rundir::run_folder {
namespace {

std::string in(Dir dir, const std::string& name) { return dir + "/" + name; }

}  // namespace

std::string experiment(Dir dir) { return in(dir, kExperimentFile); }
std::string manifest(Dir dir) { return in(dir, kManifestFile); }
std::string records(Dir dir) { return in(dir, "records"); }
std::string drivers(Dir dir) { return in(dir, "drivers"); }
std::string driver(Dir dir, const std::string& platform) {
  return drivers(dir) + "/" + platform + ".json";
}
std::string logs(Dir dir) { return in(dir, "logs"); }
std::string shard_log(Dir dir, const std::string& shard, bool retry) {
  return logs(dir) + "/" + shard + (retry ? ".retry" : "") + ".log";
}
std::string parts(Dir dir) { return in(dir, "parts"); }
std::string slices(Dir dir) { return in(dir, "slices"); }
std::string slurm(Dir dir) { return in(dir, "slurm"); }
std::string slurm_jobs(Dir dir) { return slurm(dir) + "/jobs.json"; }
std::string progress(Dir dir) { return in(dir, "progress.json"); }
std::string summary(Dir dir) { return in(dir, "summary.md"); }
std::string study(Dir dir) { return in(dir, "study.json"); }
std::string timing(Dir dir) { return in(dir, kTimingFile); }

std::string analysis(Dir dir) { return in(dir, "analysis"); }
std::string tally(Dir dir) { return analysis(dir) + "/" + kTallyFile; }
std::string figure_data(Dir dir) { return analysis(dir) + "/" + kFigureDataFile; }
std::string figures(Dir dir) { return in(dir, "figures"); }
std::string figure_index(Dir dir) { return figures(dir) + "/index.json"; }
std::string report(Dir dir) { return in(dir, "report"); }
std::string report_pdf(Dir dir) { return report(dir) + "/report.pdf"; }
std::string report_html(Dir dir) { return report(dir) + "/report.html"; }
std::string audit(Dir dir) { return in(dir, "audit"); }
std::string reproduce(Dir dir) { return in(dir, "reproduce"); }
std::string reproducer_source(Dir dir, const std::string& platform, const std::string& kind,
                              int view, std::uint64_t index) {
  return reproduce(dir) + "/" + platform + "." + kind + ".v" + std::to_string(view) + "." +
         std::to_string(index) + ".c";
}
std::string named_audit(Dir dir, const std::string& name) { return in(dir, "audit-" + name); }
std::string audit_between(Dir dir, const std::string& a, const std::string& b) {
  return in(dir, "audit-" + a + "-vs-" + b);
}
std::string named_bisect(Dir dir, const std::string& name) { return in(dir, "bisect-" + name); }
std::string audit_json(Dir audit_dir) { return in(audit_dir, kAuditJsonFile); }
std::string audit_md(Dir audit_dir) { return in(audit_dir, kAuditMdFile); }
std::string upgrade_summary(Dir dir, const std::string& build) {
  return in(dir, "upgrade-summary-" + build + ".json");
}
std::string upgrade_pictures(Dir dir) { return in(dir, "upgrade-pictures"); }
std::string bisect(Dir dir) { return in(dir, "bisect"); }
std::string bisection(Dir bisect_dir) { return in(bisect_dir, "bisect.json"); }
std::string bisection_md(Dir bisect_dir) { return in(bisect_dir, "bisect.md"); }

}  // namespace ra::rundir::run_folder
