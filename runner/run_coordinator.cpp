#include "runner/run_coordinator.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <thread>

#include "metrics/conformance.h"
#include "platforms/platform_probe.h"
#include "platforms/renderer_check.h"
#include "rundir/experiment.h"
#include "rundir/manifest.h"
#include "rundir/run_folder.h"
#include "rundir/shard.h"
#include "runner/recorded_failures.h"
#include "runner/prepare_run_dir.h"
#include "runner/run_plan.h"
#include "runner/progress_meter.h"
#include "rundir/shard.h"
#include "runner/shard_recovery.h"
#include "runner/worker_pool.h"
#include "util/atomic_file.h"
#include "util/dir_lock.h"
#include "util/errors.h"
#include "util/interrupt.h"
#include "util/json_file.h"
#include "util/worker_program.h"

namespace fs = std::filesystem;

namespace ra::runner {
namespace {

volatile std::sig_atomic_t g_interrupted = 0;
void on_signal(int) { g_interrupted = 1; }


// While a run goes on: SIGINT, SIGTERM and a closed terminal (SIGHUP) stop it as Ctrl-C does
// (workers reaped, temporaries removed, the manifest saying "interrupted"); SIGPIPE is ignored, so
// that a server that died before reading its command fails the write instead. The handlers before
// are restored at the end.
class RunSignals {
 public:
  RunSignals() : stop_(on_signal) {
    struct sigaction ignore_pipe {};
    ignore_pipe.sa_handler = SIG_IGN;
    sigemptyset(&ignore_pipe.sa_mask);
    sigaction(SIGPIPE, &ignore_pipe, &old_pipe_);
  }
  void restore() {
    if (restored_) return;
    restored_ = true;
    stop_.restore();
    sigaction(SIGPIPE, &old_pipe_, nullptr);
  }
  ~RunSignals() { restore(); }

 private:
  util::StopSignals stop_;
  struct sigaction old_pipe_ {};
  bool restored_ = false;
};

// A GL worker holds its view's colour buffer, 4 bytes per pixel (RGBA8), for the whole shard; past
// this size the run says how much memory it will take, once, before it starts.
constexpr double kLargeWorkerBytes = 256.0 * 1024 * 1024;

void note_large_views(const std::vector<rundir::Shard>& shards, const rundir::Experiment& exp, int jobs) {
  double largest = 0;
  const geometry::View* at = nullptr;
  for (const geometry::View& v : exp.views) {
    const bool used = std::any_of(shards.begin(), shards.end(),
                                  [&](const rundir::Shard& s) { return s.view == v.id; });
    const double bytes = double(v.width) * v.height * 4;
    if (used && bytes > largest) largest = bytes, at = &v;
  }
  if (!at || largest < kLargeWorkerBytes) return;
  jobs = int(std::min<size_t>(size_t(jobs), shards.size()));
  const double gib = 1024.0 * 1024 * 1024;
  std::fprintf(stderr,
               "renderaudit: note: views of %d x %d pixels need about %.2f GiB of memory in each "
               "GL worker (its colour buffer); %d workers at once: about %.2f GiB\n",
               at->width, at->height, largest / gib, jobs, largest * jobs / gib);
}

nlohmann::json drivers_json(const std::string& dir) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& e : fs::directory_iterator(rundir::run_folder::drivers(dir))) {
    if (e.path().extension() != ".json") continue;
    try {
      out[e.path().stem().string()] =
          util::parse_json_document(util::read_file(e.path().string()), e.path().string());
    } catch (const std::exception&) {
    }
  }
  return out;
}

// What follows from each item's end: a success is counted (with its shard's wall seconds); a
// crash or hang queues a re-run first, then the halves of a bisection, ahead of the shards not
// yet started; a driver mismatch stops the run; a worker's own error is noted.
struct ItemEnds {
  RunResult& result;
  ProgressMeter& progress;
  ShardRecovery& recovery;
  std::deque<WorkItem>& todo;
  std::map<std::string, double>& shard_seconds;
  bool show;

  void operator()(const WorkerEvent& e) {
    switch (e.kind) {
      case WorkerEvent::Kind::kSucceeded:
        if (!e.item.is_part()) shard_seconds[e.item.shard.id()] = e.item_s;
        return conclude(e.item, WorkOutcome::kOk, "");
      case WorkerEvent::Kind::kCrashed:
        return conclude(e.item, WorkOutcome::kCrash, e.reason);
      case WorkerEvent::Kind::kTimedOut:
        return conclude(e.item, WorkOutcome::kTimeout, e.reason);
      case WorkerEvent::Kind::kDriverMismatch:
        progress.shard_finished();
        result.failures.push_back({e.item.shard.id(), e.reason + ": " + e.words + e.log});
        if (result.wrong_renderer.empty()) result.wrong_renderer = e.words;
        return;
      case WorkerEvent::Kind::kFailed: {
        progress.shard_finished();
        const std::string why = e.reason + (e.words.empty() ? "" : ": " + e.words);
        std::fprintf(stderr, "%srenderaudit: shard %s: worker %s\n", show ? "\n" : "",
                     e.item.shard.id().c_str(), why.c_str());
        result.failures.push_back({e.item.shard.id(), why + e.log});
        return;
      }
    }
  }

  void conclude(const WorkItem& w, WorkOutcome outcome, const std::string& reason) {
    if (outcome == WorkOutcome::kOk) {
      progress.item_done(w);
      if (!w.is_part()) progress.shard_finished(), ++result.shards_run;
    } else if (!w.is_part()) {
      result.failures.push_back({w.shard.id(), reason + (w.attempt == 1 ? "; re-running it"
                                                                        : "; bisecting it")});
    }
    bool assembled = false;
    const std::vector<WorkItem> next = recovery.on_finished(w, outcome, reason, &assembled);
    for (auto it = next.rbegin(); it != next.rend(); ++it) todo.push_front(*it);
    if (assembled) progress.shard_finished(), ++result.shards_run;
  }
};

// DIR/manifest.json as this invocation starts: what an earlier invocation wrote (an unreadable
// file: nothing), this invocation added to its invocations, the status "running". Throws
// UserError when the directory's records were judged by other conformance rules.
rundir::RunManifest starting_manifest(const RunOptions& options, const rundir::Experiment& exp, int jobs,
                              size_t shards, size_t shards_to_run, const std::string& path) {
  // A damaged manifest is kept beside, never overwritten unseen: it holds the start time and the
  // earlier invocations.
  nlohmann::json earlier;
  try {
    earlier = rundir::read_manifest_json(path);
  } catch (const util::UserError& e) {
    std::string kept;
    try {
      kept = util::keep_damaged_copy(path, false);  // never over a copy an earlier run kept
    } catch (const std::runtime_error& why) {
      throw util::UserError(std::string(e.what()) + "; and it cannot be kept (" + why.what() +
                            "): nothing was run");
    }
    std::fprintf(stderr,
                 "renderaudit: %s\nrenderaudit: kept it as %s; this run starts a new manifest "
                 "(the start time and earlier invocations are in the kept file)\n",
                 e.what(), kept.c_str());
  }
  rundir::RunManifest m = rundir::read_manifest(earlier, path);
  const std::string started = rundir::utc_now_iso8601();
  if (m.started.empty()) m.started = started;
  m.schema = "renderaudit-manifest";
  m.schema_version = rundir::kManifestSchemaVersion;
  m.tool = {{"name", "renderaudit"}, {"version", rundir::project_version()}, {"commit", rundir::project_commit()}};
  // A directory's records are judged by one version of the conformance rules.
  const int rules = m.rules_judged_by();
  if (rules != 0 && rules != metrics::kConformanceRulesVersion)
    throw util::UserError(path + ": its records were judged by conformance rules " +
                          std::to_string(rules) + ", this renderaudit judges by " +
                          std::to_string(metrics::kConformanceRulesVersion) +
                          "; resuming would mix them: run into a new directory");
  m.conformance_rules = metrics::kConformanceRulesVersion;
  m.experiment = rundir::ManifestExperiment{exp.name, options.experiment_path, exp.hash, exp.seed,
                                    exp.platforms};
  m.host = rundir::host_description();
  // which platforms' shards this directory is meant to hold (--platform), for `status`
  m.platforms_run.reset();
  if (!options.only_platforms.empty()) m.platforms_run = options.only_platforms;
  if (options.slice) m.slice = rundir::ManifestSlice{options.slice->index, options.slice->count, shards};
  if (!m.invocations) m.invocations.emplace();
  rundir::ManifestInvocation now;
  now.started = started;
  now.jobs = uint64_t(jobs);
  now.shards_to_run = shards_to_run;
  m.invocations->push_back(now);
  m.status = "running";
  return m;
}

// The manifest as the invocation ends: drivers, times, how well the cores were used, failures,
// the crash and timeout records the directory holds, and the status.
void finish_manifest(rundir::RunManifest& m, const RunOptions& options, const std::string& dir, int jobs,
                     double elapsed_s, double busy_s, const std::vector<rundir::Shard>& shards,
                     RunResult& result) {
  m.drivers = drivers_json(dir);
  m.finished = rundir::utc_now_iso8601();
  rundir::ManifestInvocation& inv = m.invocations->back();
  inv.elapsed_s = elapsed_s;
  // How well the cores were used: worker-seconds, and the core-seconds no worker used (the tail
  // when the last shards run alone, plus the coordinator's own gaps)
  inv.shard_order = options.shard_order == RunOptions::ShardOrder::kPlan
                        ? "plan" : "largest-expected-cost-first";
  inv.worker_busy_s = busy_s;
  inv.worker_processes = result.worker_processes;
  inv.workers = options.serve_shards ? "serve-shards" : "per-shard";
  inv.idle_core_s = std::max(0.0, jobs * elapsed_s - busy_s);
  size_t complete = 0;
  for (const rundir::Shard& s : shards) complete += fs::exists(s.records_path(dir));
  m.shards = rundir::ManifestShardCounts{shards.size(), complete, std::nullopt};
  m.failures.emplace();
  for (const auto& f : result.failures) m.failures->push_back({f.shard, f.reason});
  if (!result.damaged.empty()) {
    if (!m.damaged_shards_redone) m.damaged_shards_redone.emplace();
    for (const auto& d : result.damaged) m.damaged_shards_redone->push_back({d.shard, d.reason});
  }
  // What the records hold, whoever wrote them (an earlier invocation, a merge), with the reasons
  // this invocation and the manifest before it gave.
  std::map<std::string, std::string> reasons;
  add_failure_reasons(m, &reasons);
  for (const FailedPrimitive& f : result.failed_primitives)
    reasons[failure_key(f.shard, f.index)] = f.reason;
  result.failed_primitives_held = failed_primitives_in_records(dir, shards, reasons);
  m.failed_primitives.emplace();
  for (const FailedPrimitive& f : result.failed_primitives_held)
    m.failed_primitives->push_back({f.shard, f.index, metrics::status_name(f.status), f.reason});
  result.shards_complete = complete;
  if (!result.wrong_renderer.empty()) m.wrong_renderer = result.wrong_renderer;
  m.status = result.interrupted                    ? "interrupted"
             : !result.wrong_renderer.empty()      ? "wrong-renderer"
             : complete != shards.size()           ? "failed"
             : !m.failed_primitives->empty()       ? "complete-with-failed-primitives"
                                                   : "complete";
}

}  // namespace

RunResult run_experiment(const RunOptions& options) {
  const rundir::Experiment exp = rundir::load_experiment(options.experiment_path);
  RunResult result;
  result.run_dir = options.out_dir.empty() ? "outputs/" + exp.name : options.out_dir;
  const std::string& dir = result.run_dir;
  const int jobs = options.jobs > 0 ? options.jobs : int(std::max(1u, std::thread::hardware_concurrency()));
  const double timeout_s = options.timeout_s > 0 ? options.timeout_s : exp.shard_timeout_s;

  // The plan. A platform that cannot draw here (no such device, a missing library or driver)
  // stops the run before its directory is touched, rather than filling it with failed shards.
  require_experiment_platforms(exp, options.experiment_path, options.only_platforms);
  {
    std::vector<rundir::PlatformSpec> specs;
    for (const std::string& p : options.only_platforms.empty() ? exp.platforms : options.only_platforms)
      specs.push_back(rundir::experiment_platform(exp, p));
    platforms::require_platforms_draw(specs, options.experiment_path);
  }
  const std::vector<rundir::Shard> shards = shards_of_run(exp, options.only_platforms, options.slice);
  const std::unique_ptr<util::DirLock> lock = prepare_run_dir(exp, dir);
  note_large_views(shards, exp, jobs);
  RunQueue queue = queue_shards(shards, exp, dir,
                                options.shard_order == RunOptions::ShardOrder::kLargestCostFirst,
                                timeout_s);
  std::deque<WorkItem>& todo = queue.todo;
  result.shards_done_before = queue.done_before;
  result.damaged = queue.damaged;
  result.shards_total = shards.size();
  for (const rundir::Shard& s : shards) result.primitives_total += s.size();

  // The manifest says "running" before any worker starts.
  const std::string manifest_path = rundir::run_folder::manifest(dir);
  rundir::RunManifest manifest =
      starting_manifest(options, exp, jobs, shards.size(), todo.size(), manifest_path);
  rundir::write_manifest(manifest_path, manifest);

  // The workers, and what follows from each item's end.
  RunSignals signals;
  ProgressMeter progress(exp, todo);
  const bool show = options.progress && progress.on_terminal();  // a line rewritten in place
  ShardRecovery recovery(dir, exp, timeout_s);
  platforms::RendererCheck renderer_check(dir, options.expect_renderer);
  // wall seconds of each shard's worker (whole shards run at the first attempt), kept across
  // invocations: what a cost model or a simulation of more machines can learn from
  std::map<std::string, double> shard_seconds = manifest.shard_seconds.value_or(
      std::map<std::string, double>{});
  ItemEnds on_event{result, progress, recovery, todo, shard_seconds, show};
  const std::string program =
      options.worker_program.empty() ? util::worker_program() : options.worker_program;
  WorkerPool pool(
      {program, dir, jobs, options.serve_shards, show,
       rundir::records_extension(exp.records_format)},
      [&](const WorkItem& w) { return recovery.records_dir(w); }, std::ref(on_event));
  const std::string this_host = manifest.host.value("hostname", "");
  while (!todo.empty() || !pool.empty()) {
    if (g_interrupted) {
      result.interrupted = true;
      break;  // the pool's end kills the workers
    }
    if (const std::string wrong = renderer_check.mismatch(); !wrong.empty())
      result.wrong_renderer = wrong;
    if (!result.wrong_renderer.empty()) {  // the check's, or a worker's driver mismatch
      todo.clear();
      break;
    }
    if (pool.serve(todo)) continue;  // reap everything that is ready before sleeping
    pool.enforce_time_limits();
    progress.write_file(dir, this_host, pool, result.failures, false);
    if (options.progress) progress.show(result.failures.size());
    // Sleep up to 5 ms, waking at once when a server replies (the next shard is sent at once).
    pool.wait(5);
  }
  progress.end_line();
  pool.stop_all();  // no worker runs past this point
  progress.write_file(dir, this_host, pool, result.failures, true);
  fs::remove_all(ShardRecovery::parts_dir(dir));
  remove_temporaries(dir);  // what killed (timed-out) workers left half-written
  signals.restore();

  // The manifest says how the invocation ended.
  result.worker_processes = pool.processes_started();
  result.failed_primitives = recovery.failed_primitives();
  manifest.shard_seconds = shard_seconds;
  result.seconds = progress.elapsed_s();
  finish_manifest(manifest, options, dir, jobs, result.seconds, pool.busy_seconds(), shards,
                  result);
  rundir::write_manifest(manifest_path, manifest);
  return result;
}

}  // namespace ra::runner
