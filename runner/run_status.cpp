// Where a run stands (see the header).
#include "runner/run_status.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include "rundir/experiment.h"
#include "rundir/manifest.h"
#include "rundir/run_experiment.h"
#include "rundir/run_folder.h"
#include "rundir/shard.h"
#include "rundir/shard_records.h"
#include "rundir/slicing.h"
#include "util/atomic_file.h"
#include "util/child_process.h"
#include "util/dir_lock.h"
#include "util/duration_text.h"
#include "util/errors.h"
#include "util/json_file.h"
#include "util/number_text.h"
#include "util/parallel.h"

namespace fs = std::filesystem;

namespace ra::runner {
namespace {

bool is_pending(const std::string& state) {
  return state == "PENDING" || state == "REQUEUED" || state == "CONFIGURING" ||
         state == "REQUEUE_HOLD" || state == "REQUEUE_FED" || state == "RESIZING";
}

// The Slurm jobs of DIR/slurm/jobs.json that squeue still lists (array tasks one by one).
void ask_squeue(RunStatus& s, const std::string& squeue) {
  util::ChildSpec spec;
  spec.argv = {squeue, "-h", "-r", "-j", s.array_job + "," + s.gather_job, "-o", "%i|%T|%r"};
  spec.capture_output = true;
  spec.stdin_null = true;
  const util::ProgramResult r = util::run_program(spec);
  if (!r.exited_ok()) {
    // jobs Slurm has forgotten (they ended long ago) are not an error
    if (r.output.find("Invalid job id") == std::string::npos)
      s.squeue_error =
          r.exit_code() == 127 ? "squeue not found" : r.output.substr(0, r.output.find('\n'));
    return;
  }
  std::istringstream lines(r.output);
  for (std::string line; std::getline(lines, line);) {
    const size_t a = line.find('|'), b = line.find('|', a + 1);
    if (a == std::string::npos || b == std::string::npos) continue;
    s.jobs.push_back({line.substr(0, a), line.substr(a + 1, b - a - 1), line.substr(b + 1)});
  }
}

}  // namespace

std::string RunStatus::state() const {
  if (!writers.empty()) return "running";
  bool queued = false;
  for (const auto& j : jobs) {
    if (j.state == "RUNNING" || j.state == "COMPLETING") return "running";
    queued = queued || is_pending(j.state);
  }
  if (queued) return "queued";
  if (!damaged.empty()) return "damaged";
  if (planned > 0 && done == planned && manifest_status.rfind("complete", 0) == 0)
    return "complete";
  // squeue failed and the gather has not ended: the jobs may be queued, running or gone
  if (slurm && !squeue_error.empty() && gather_exit < 0) return "unknown";
  if (manifest_status == "interrupted") return "interrupted";
  if (manifest_status == "failed" || failed > 0 || (gather_exit > 0)) return "failed";
  return "incomplete";
}

RunStatus read_run_status(const std::string& dir, const std::string& squeue, bool check_seals) {
  if (!fs::exists(rundir::run_folder::experiment(dir)))
    throw util::UserError(dir + ": not a run directory (no experiment.toml)");
  RunStatus s;
  s.dir = dir;
  const rundir::Experiment exp = rundir::load_run_experiment(dir);
  s.experiment = exp.name;
  const rundir::RunManifest manifest =
      rundir::read_manifest_file_or_empty(rundir::run_folder::manifest(dir));
  s.manifest_status = manifest.status;
  // the name the run was given (a copy named experiment.toml would name it "experiment")
  if (manifest.experiment && !manifest.experiment->name.empty())
    s.experiment = manifest.experiment->name;

  // Where shards can be: DIR, and the slices of a Slurm run beneath it.
  std::vector<std::string> sources = {dir};
  std::error_code ec;
  std::vector<std::string> slice_dirs;
  for (const auto& e : fs::directory_iterator(rundir::run_folder::slices(dir), ec))
    if (fs::exists(rundir::run_folder::experiment(e.path().string())))
      slice_dirs.push_back(e.path().string());
  std::sort(slice_dirs.begin(), slice_dirs.end());
  sources.insert(sources.end(), slice_dirs.begin(), slice_dirs.end());

  std::vector<rundir::Shard> shards = rundir::plan_shards(exp);
  // a run of some platforms only (--platform): the manifest of DIR or of its first slice says so
  rundir::RunManifest platforms_from = manifest;
  if (!manifest.platforms_run && !slice_dirs.empty())
    platforms_from =
        rundir::read_manifest_file_or_empty(rundir::run_folder::manifest(slice_dirs.front()));
  if (platforms_from.platforms_run) {
    const auto& keep = *platforms_from.platforms_run;
    shards.erase(std::remove_if(shards.begin(), shards.end(),
                                [&](const rundir::Shard& sh) {
                                  return std::find(keep.begin(), keep.end(), sh.platform) ==
                                         keep.end();
                                }),
                 shards.end());
  }
  if (manifest.slice && slice_dirs.empty()) {
    shards = rundir::shards_of_slice(shards, exp, rundir::Slice{manifest.slice->index, manifest.slice->count});
    s.slice_index = manifest.slice->index;
    s.slice_count = manifest.slice->count;
  }
  s.planned = shards.size();

  std::set<std::string> running, failed;
  for (const std::string& src : sources) {
    const std::string holder = util::DirLock::current_holder(src);
    if (!holder.empty()) {
      WriterStatus w{src, holder, read_run_progress(src)};
      running.insert(w.progress.running.begin(), w.progress.running.end());
      failed.insert(w.progress.failed.begin(), w.progress.failed.end());
      s.writers.push_back(std::move(w));
    } else {
      const rundir::RunManifest m =
          src == dir ? manifest
                     : rundir::read_manifest_file_or_empty(rundir::run_folder::manifest(src));
      for (const rundir::ManifestShardNote& f : m.failures_or_none()) failed.insert(f.shard);
    }
  }
  // Each shard's files judged by the seal rule (read whole, on every core), unless told not to.
  std::vector<char> have(shards.size(), 0);
  std::vector<std::vector<std::string>> damaged(shards.size());
  util::run_in_parallel(shards.size(), 0, [&](std::size_t i) {
    for (const std::string& src : sources) {
      try {
        const rundir::ShardRecordsFile f = rundir::find_shard_records(src, shards[i], check_seals);
        if (!f.path.empty() && f.damage.empty()) have[i] = 1;
        if (!f.damage.empty()) damaged[i].push_back(f.path + ": " + f.damage);
      } catch (const util::UserError& e) {  // both formats of the shard
        damaged[i].push_back(e.what());
      }
    }
  });
  s.seals_checked = check_seals;
  for (std::size_t i = 0; i < shards.size(); ++i) {
    const rundir::Shard& sh = shards[i];
    const std::string id = sh.id();
    if (!have[i]) s.damaged.insert(s.damaged.end(), damaged[i].begin(), damaged[i].end());
    if (have[i])
      ++s.done;
    else if (!damaged[i].empty())
      continue;  // neither done nor waiting: listed as damaged
    else if (running.count(id))
      ++s.running;
    else if (failed.count(id))
      ++s.failed;
    else
      ++s.waiting;
  }
  for (const auto& w : s.writers)
    if (w.progress.left_s >= 0) s.left_s = std::max(s.left_s, w.progress.left_s);

  const nlohmann::json jobs = util::read_json_or_null(rundir::run_folder::slurm_jobs(dir));
  if (jobs.is_object()) {
    s.slurm = true;
    s.array_job = jobs.value("array_job", "");
    s.gather_job = jobs.value("gather_job", "");
    s.slices = jobs.value("slices", 0);
    ask_squeue(s, squeue);
    for (const auto& j : s.jobs)
      if (j.id.rfind(s.array_job + "_", 0) == 0 && is_pending(j.state)) ++s.slices_not_started;
    try {
      s.gather_exit = std::stoi(util::read_file(rundir::run_folder::slurm(dir) + "/gather.exit"));
    } catch (const std::exception&) {
    }
  }
  return s;
}

std::string format_run_status(const RunStatus& s) {
  std::ostringstream o;
  const double pct = s.planned ? 100.0 * s.done / s.planned : 0;
  const std::string percent = util::fixed(pct, 0) + "%";
  o << s.dir << ": experiment " << s.experiment << ": " << s.state();
  if (s.slice_count > 0)
    o << " (slice " << s.slice_index << " of " << s.slice_count
      << ": its own shards; `renderaudit merge` joins the slices into one run to analyse)";
  o << "\n";
  o << "  shards: " << s.planned << " planned, " << s.done << " done (" << percent << "), " << s.running
    << " running, " << s.failed << " failed, " << s.waiting << " waiting"
    << (s.damaged.empty() ? ""
        : ", " + std::to_string(s.damaged.size()) +
              (s.damaged.size() == 1 ? " damaged file" : " damaged files"))
    << "\n";
  if (!s.seals_checked)
    o << "  seals not checked (--quick): a file counts as done when it exists; without --quick "
         "every file is read and damaged ones are named\n";
  for (std::size_t i = 0; i < s.damaged.size() && i < 20; ++i)
    o << "  damaged: " << s.damaged[i] << "\n";
  if (s.damaged.size() > 20) o << "  ... and " << s.damaged.size() - 20 << " more damaged\n";
  if (!s.damaged.empty() && s.writers.empty())
    o << "  `renderaudit run` of this directory redoes the damaged shards (each file is kept as "
         ".damaged, or .damaged.2, ... beside copies kept earlier)\n";
  for (const auto& w : s.writers) {
    o << "  writer " << w.dir << ": " << w.holder;
    if (!w.progress.host.empty())
      o << "; " << w.progress.shards_finished << " of " << w.progress.shards_to_run
        << " shards, left " << util::duration_text(w.progress.left_s, "unknown");
    o << "\n";
  }
  if (s.slurm) {
    size_t tasks_running = 0, tasks_pending = 0;
    std::string gather = "not listed by squeue";
    for (const auto& j : s.jobs) {
      if (j.id == s.gather_job) {
        gather = j.state + (j.reason.empty() || j.reason == "None" ? "" : " (" + j.reason + ")");
      } else {
        tasks_running += j.state == "RUNNING" || j.state == "COMPLETING";
        tasks_pending += is_pending(j.state);
      }
    }
    if (s.gather_exit >= 0) gather = "ended, exit " + std::to_string(s.gather_exit);
    o << "  slurm: array job " << s.array_job << " (" << s.slices << " slices): " << tasks_running
      << " running, " << tasks_pending << " pending; gather job " << s.gather_job << ": " << gather
      << "\n";
    if (!s.squeue_error.empty()) o << "  squeue: " << s.squeue_error << "\n";
    if (s.state() == "unknown")
      o << "  the scheduler could not be asked, so whether the jobs are queued, running or gone "
           "is not known; ask again when squeue answers\n";
  }
  if (s.state() == "running" || s.state() == "queued") {
    o << "  time left: ";
    if (s.left_s >= 0)
      o << "about " << util::duration_text(s.left_s, "unknown") << " for the running writers";
    else
      o << "not known yet";
    if (s.slices_not_started) o << ", then " << s.slices_not_started << " slices not started";
    o << "\n";
  }
  if (!s.manifest_status.empty()) o << "  manifest: " << s.manifest_status << "\n";
  return o.str();
}

nlohmann::json to_json(const RunStatus& s) {
  nlohmann::json writers = nlohmann::json::array();
  for (const auto& w : s.writers)
    writers.push_back({{"dir", w.dir}, {"holder", w.holder}, {"progress", to_json(w.progress)}});
  nlohmann::json j = {{"dir", s.dir},       {"experiment", s.experiment},
                      {"state", s.state()}, {"planned", s.planned},
                      {"done", s.done},     {"running", s.running},
                      {"failed", s.failed}, {"waiting", s.waiting},
                      {"writers", writers}, {"manifest_status", s.manifest_status},
                      {"left_s", seconds_or_null(s.left_s)},
                      {"damaged", s.damaged},  {"seals_checked", s.seals_checked}};
  if (s.slice_count > 0) j["slice"] = {{"index", s.slice_index}, {"count", s.slice_count}};
  if (s.slurm) {
    nlohmann::json jobs = nlohmann::json::array();
    for (const auto& job : s.jobs)
      jobs.push_back({{"id", job.id}, {"state", job.state}, {"reason", job.reason}});
    j["slurm"] = {{"array_job", s.array_job},     {"gather_job", s.gather_job},
                  {"slices", s.slices},           {"jobs", jobs},
                  {"gather_exit", s.gather_exit}, {"slices_not_started", s.slices_not_started}};
  }
  return j;
}

}  // namespace ra::runner
