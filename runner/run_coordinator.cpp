#include "runner/run_coordinator.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <thread>

#include "util/atomic_file.h"
#include "util/child_process.h"
#include "util/dir_lock.h"
#include "util/duration_text.h"
#include "util/errors.h"
#include "metrics/conformance.h"
#include "runner/run_dir.h"
#include "runner/run_progress.h"
#include "runner/shard_cost.h"
#include "runner/shard_file.h"
#include "runner/experiment.h"
#include "runner/manifest.h"
#include "runner/recorded_failures.h"
#include "platforms/platform_probe.h"
#include "platforms/renderer_check.h"
#include "runner/shard.h"
#include "runner/shard_recovery.h"
#include "runner/shard_server.h"
#include "runner/worker_program.h"

namespace fs = std::filesystem;

namespace ra {
namespace {

volatile std::sig_atomic_t g_interrupted = 0;
void on_signal(int) { g_interrupted = 1; }

using Clock = std::chrono::steady_clock;

// A worker process: one shard's (or part's), or a server of one platform's shards.
struct Running {
  WorkItem item;                 // what it runs now (a server: valid while busy)
  bool busy = true;              // a server between shards is idle
  Clock::time_point started;     // when `item` started
  Clock::time_point spawned;     // when the process started
  int message_fd = -1;           // the worker's message pipe
  int command_fd = -1;           // a server's stdin; -1: a one-shard worker, or a server told to end
  bool server = false;
  std::string unread;            // message-pipe bytes not yet a whole line
  std::string words;             // what it said that is not a reply: its last words
  Clock::time_point told_to_end;  // a server: when its input was closed (it has no shard left)
};

// How long a server may take to exit once told that no shard is left: its shards are all
// committed, so one that hangs in its driver's teardown is killed, and nothing is lost.
constexpr double kServerExitGraceS = 10;

// A worker: its own process group (a timeout kills all it started), dies with this process, its
// output in its log, and a message pipe for its last words (they reach us even when the disk of
// the log is full).
Child spawn_worker(const std::string& program, const std::string& dir, const WorkItem& item,
                   const std::string& records_dir) {
  const Shard& s = item.shard;
  ChildSpec spec;
  spec.argv = {program, "worker", dir, s.platform, kind_name(s.kind), std::to_string(s.view),
               std::to_string(s.begin), std::to_string(s.end), "--records-dir", records_dir};
  spec.set_env = {"RA_RENDER_ATTEMPT=" + std::to_string(item.attempt)};
  spec.log_to(dir + "/logs/" + s.id() + (item.attempt > 1 ? ".retry" : "") + ".log");
  spec.stdin_null = true;
  spec.own_process_group = true;
  spec.message_pipe = true;
  return start_child(spec);
}

std::string log_path(const std::string& dir, const WorkItem& item) {
  return dir + "/logs/" + item.shard.id() + (item.attempt > 1 ? ".retry" : "") + ".log";
}

// A server of `platform`'s shards (runner/shard_server.h), set up as spawn_worker's workers are.
Child spawn_server(const std::string& program, const std::string& dir, const WorkItem& first) {
  ChildSpec spec;
  spec.argv = {program, "serve-shards", dir, first.shard.platform};
  spec.set_env = {"RA_RENDER_ATTEMPT=1"};
  spec.log_to(log_path(dir, first));  // until the first command names it again
  spec.command_pipe = true;
  spec.own_process_group = true;
  spec.message_pipe = true;
  return start_child(spec);
}

// Reads what the worker said since last time: the ids of the shards it reports done (a server's
// replies), in order; anything else is kept as its last words.
std::vector<std::string> read_replies(Running& r) {
  r.unread += drain_fd(r.message_fd);
  std::vector<std::string> done;
  size_t start = 0;
  for (size_t nl; (nl = r.unread.find('\n', start)) != std::string::npos; start = nl + 1) {
    const std::string line = r.unread.substr(start, nl - start);
    std::string id;
    if (parse_shard_done(line, &id))
      done.push_back(id);
    else
      r.words += line + "\n";
  }
  r.unread.erase(0, start);
  return done;
}

// What a finished worker said that was not a reply (the error it stopped on), one line.
std::string last_words(Running& r) {
  read_replies(r);
  std::string text = r.words + r.unread;
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text;
}

// Sends `item` to a server; false when it is gone (it will be reaped as such).
bool send_command(Running& r, const std::string& dir, const WorkItem& item,
                  const std::string& records_dir) {
  const std::string line =
      shard_command_line({item.shard, records_dir, log_path(dir, item)}) + "\n";
  size_t done = 0;
  while (done < line.size()) {
    const ssize_t n = ::write(r.command_fd, line.data() + done, line.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += size_t(n);
  }
  return true;
}

// A GL worker holds its view's colour buffer, 4 bytes per pixel (RGBA8), for the whole shard; past
// this size the run says how much memory it will take, once, before it starts.
constexpr double kLargeWorkerBytes = 256.0 * 1024 * 1024;

void note_large_views(const std::vector<Shard>& shards, const Experiment& exp, int jobs) {
  double largest = 0;
  const View* at = nullptr;
  for (const View& v : exp.views) {
    const bool used = std::any_of(shards.begin(), shards.end(),
                                  [&](const Shard& s) { return s.view == v.id; });
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
  for (const auto& e : fs::directory_iterator(dir + "/drivers")) {
    if (e.path().extension() != ".json") continue;
    try {
      out[e.path().stem().string()] = nlohmann::json::parse(read_file(e.path().string()));
    } catch (const std::exception&) {
    }
  }
  return out;
}

}  // namespace

RunResult run_experiment(const RunOptions& options) {
  const Experiment exp = load_experiment(options.experiment_path);
  RunResult result;
  result.run_dir = options.out_dir.empty() ? "outputs/" + exp.name : options.out_dir;
  const std::string& dir = result.run_dir;
  const int jobs = options.jobs > 0 ? options.jobs : int(std::max(1u, std::thread::hardware_concurrency()));
  const double timeout_s = options.timeout_s > 0 ? options.timeout_s : exp.shard_timeout_s;
  std::string program = options.worker_program;
  if (program.empty()) program = worker_program();

  for (const auto& p : options.only_platforms)
    if (std::find(exp.platforms.begin(), exp.platforms.end(), p) == exp.platforms.end())
      throw UserError(options.experiment_path + ": --platform " + p +
                      " is not one of the experiment's platforms");
  // A platform that cannot draw here (no such device, a missing library or driver) stops the
  // run before its directory is touched, rather than filling it with failed shards.
  {
    std::vector<PlatformSpec> specs;
    for (const std::string& p : options.only_platforms.empty() ? exp.platforms : options.only_platforms)
      specs.push_back(experiment_platform(exp, p));
    require_platforms_draw(specs, options.experiment_path);
  }
  std::vector<Shard> all = plan_shards(exp);
  if (!options.only_platforms.empty()) {
    const auto& keep = options.only_platforms;
    all.erase(std::remove_if(all.begin(), all.end(), [&](const Shard& s) {
                return std::find(keep.begin(), keep.end(), s.platform) == keep.end();
              }),
              all.end());
  }
  // Every slice holds a shard, as `run --slurm --slices` requires: an empty slice would be a
  // "complete" run of nothing.
  if (options.slice && size_t(options.slice->count) > all.size())
    throw UserError("--slice " + std::to_string(options.slice->index) + "/" +
                    std::to_string(options.slice->count) + ": the run has only " +
                    std::to_string(all.size()) + " shards (allowed: N from 1 to " +
                    std::to_string(all.size()) + ")");
  if (options.slice) all = shards_of_slice(all, exp, *options.slice);
  const std::unique_ptr<DirLock> lock = prepare_run_dir(exp, dir);

  std::deque<WorkItem> todo;
  note_large_views(all, exp, jobs);
  for (const Shard& s : all) {
    const std::string path = s.records_path(dir);
    if (fs::exists(path)) {
      const std::string damage = check_shard_file(path, s.size());
      if (damage.empty()) {
        ++result.shards_done_before;  // finished by an earlier invocation: kept as is
        continue;
      }
      // Never counted: set aside (not deleted: it is evidence) and redone.
      std::fprintf(stderr, "renderaudit: %s: not a complete shard file: %s; redoing shard %s\n",
                   path.c_str(), damage.c_str(), s.id().c_str());
      fs::rename(path, path + ".damaged");
      result.damaged.push_back({s.id(), damage});
    }
    todo.push_back(WorkItem{s, "", 1, timeout_s});
  }
  result.shards_total = all.size();
  if (options.shard_order == RunOptions::ShardOrder::kLargestCostFirst) {
    std::vector<Shard> queued;
    for (const WorkItem& w : todo) queued.push_back(w.shard);
    todo.clear();
    for (Shard& s : largest_expected_cost_first(std::move(queued), exp))
      todo.push_back(WorkItem{std::move(s), "", 1, timeout_s});
  }

  nlohmann::json manifest;
  const std::string manifest_path = dir + "/manifest.json";
  if (fs::exists(manifest_path)) {
    try {
      manifest = nlohmann::json::parse(read_file(manifest_path));
    } catch (const std::exception&) {
      manifest = nlohmann::json::object();
    }
  }
  const std::string started = utc_now_iso8601();
  if (!manifest.contains("started")) manifest["started"] = started;
  manifest.update(document_header("manifest", kManifestSchemaVersion, false));
  manifest["tool"] = {{"name", "renderaudit"}, {"version", project_version()},
                      {"commit", project_commit()}};
  // A directory's records are judged by one version of the conformance rules.
  const int rules = conformance_rules_of(manifest, manifest_path);
  if (rules != 0 && rules != kConformanceRulesVersion)
    throw UserError(manifest_path + ": its records were judged by conformance rules " +
                    std::to_string(rules) + ", this renderaudit judges by " +
                    std::to_string(kConformanceRulesVersion) +
                    "; resuming would mix them: run into a new directory");
  manifest["conformance_rules"] = kConformanceRulesVersion;
  manifest["experiment"] = {{"name", exp.name}, {"file", options.experiment_path},
                            {"hash", exp.hash}, {"seed", exp.seed},
                            {"platforms", exp.platforms}};
  manifest["host"] = host_description();
  // which platforms' shards this directory is meant to hold (--platform), for `status`
  if (!options.only_platforms.empty()) manifest["platforms_run"] = options.only_platforms;
  else manifest.erase("platforms_run");
  if (options.slice) {
    manifest["slice"] = {{"index", options.slice->index}, {"count", options.slice->count},
                         {"shards", all.size()}};
  }
  manifest["invocations"].push_back({{"started", started}, {"jobs", jobs},
                                     {"shards_to_run", todo.size()}});
  manifest["status"] = "running";
  write_manifest(manifest_path, manifest);

  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  // A closed terminal (SIGHUP) stops the run as Ctrl-C does: workers reaped, temporaries removed,
  // the manifest saying "interrupted".
  struct sigaction old_int {}, old_term {}, old_hup {};
  sigaction(SIGINT, &sa, &old_int);
  sigaction(SIGTERM, &sa, &old_term);
  sigaction(SIGHUP, &sa, &old_hup);

  const bool show = options.progress && ::isatty(2);
  const auto t_start = Clock::now();
  uint64_t primitives_done = 0, primitives_todo = 0;
  for (const WorkItem& w : todo) primitives_todo += w.shard.size();
  // The time left is estimated in expected cost (runner/shard_cost.h), not in primitives: the
  // most expensive shards run first, so a rate in primitives per second would overestimate it.
  auto expected_cost = [&](const Shard& s) {
    for (const View& v : exp.views)
      if (v.id == s.view) return expected_shard_cost_us(s, v);
    return double(s.size());
  };
  double cost_todo = 0, cost_done = 0;
  for (const WorkItem& w : todo) cost_todo += expected_cost(w.shard);
  auto seconds_left = [&](double elapsed_s) {
    if (cost_done <= 0) return -1.0;
    return elapsed_s * std::max(0.0, cost_todo - cost_done) / cost_done;
  };
  const size_t shards_to_run = todo.size();

  ShardRecovery recovery(dir, exp, timeout_s);
  RendererCheck renderer_check(dir, options.expect_renderer);
  std::map<pid_t, Running> running;
  // Every exit path (an exception included) kills and reaps the workers still running.
  struct Reaper {
    std::map<pid_t, Running>& running;
    ~Reaper() { stop_all(); }
    void stop_all() {
      for (auto& [pid, r] : running) ::kill(-pid, SIGKILL);
      for (auto& [pid, r] : running) {
        wait_child(pid);
        if (r.message_fd >= 0) ::close(r.message_fd);
        if (r.command_fd >= 0) ::close(r.command_fd);
      }
      running.clear();
    }
  } reaper{running};
  size_t finished = 0;
  double busy_s = 0;  // worker-seconds, every worker from start to end
  // wall seconds of each shard's worker (whole shards run at the first attempt), kept across
  // invocations: what a cost model or a simulation of more machines can learn from
  nlohmann::json shard_seconds = manifest.value("shard_seconds", nlohmann::json::object());
  auto last_progress = Clock::now() - std::chrono::seconds(1);
  // DIR/progress.json for `renderaudit status`: every 2 s and at the end
  auto last_progress_file = Clock::now() - std::chrono::seconds(10);
  const std::string this_host = manifest["host"].value("hostname", "");
  auto progress_now = [&](bool at_end) {
    RunProgress p;
    p.host = this_host;
    p.pid = ::getpid();
    p.updated_utc = utc_now_iso8601();
    p.shards_to_run = shards_to_run;
    p.shards_finished = finished;
    for (const auto& [pid, r] : running)
      if (r.busy) p.running.push_back(r.item.shard.id());  // not a server between shards
    for (const auto& f : result.failures) p.failed.push_back(f.shard);
    p.primitives_done = primitives_done;
    p.primitives_todo = primitives_todo;
    p.elapsed_s = std::chrono::duration<double>(Clock::now() - t_start).count();
    p.left_s = seconds_left(p.elapsed_s);
    if (at_end) p.finished = true, p.left_s = 0;
    write_run_progress(dir, p);
  };
  // A worker ended: count it, and queue what follows from a crash or hang (a re-run first, then
  // the halves of a bisection, ahead of the shards not yet started).
  auto conclude = [&](const Running& r, WorkOutcome outcome, const std::string& reason) {
    const WorkItem& w = r.item;
    if (outcome == WorkOutcome::kOk) {
      primitives_done += w.shard.size();
      cost_done += expected_cost(w.shard);
      if (!w.is_part()) ++finished, ++result.shards_run;
    } else if (!w.is_part()) {
      result.failures.push_back({w.shard.id(), reason + (w.attempt == 1 ? "; re-running it"
                                                                        : "; bisecting it")});
    }
    bool assembled = false;
    const std::vector<WorkItem> next = recovery.on_finished(w, outcome, reason, &assembled);
    for (auto it = next.rbegin(); it != next.rend(); ++it) todo.push_front(*it);
    if (assembled) ++finished, ++result.shards_run;
  };
  // A shard a server may take: a whole one at its first attempt (re-runs and bisection parts get
  // processes of their own, whose crash names them alone).
  auto servable = [&](const WorkItem& w) {
    return options.serve_shards && w.attempt == 1 && !w.is_part();
  };
  // The next shard for an idle server of `platform`: the first of its platform among the next
  // 4 x jobs in the queue, which would start soon anyway (a shard of another platform waits for
  // at most that many); none: the server ends, and the queue's order (largest cost first) is
  // kept. A window of jobs: the short bench run started 16 processes, of 4 x jobs: 8.
  auto next_for_server = [&](const std::string& platform) {
    auto it = todo.begin();
    for (int k = 0; k < 4 * jobs && it != todo.end(); ++k, ++it)
      if (it->shard.platform == platform && servable(*it)) return it;
    return todo.end();
  };
  // A worker finished `r.item` well (its exit, or a server's reply).
  auto succeeded = [&](Running& r, double item_s) {
    if (!r.item.is_part()) shard_seconds[r.item.shard.id()] = item_s;
    conclude(r, WorkOutcome::kOk, "");
  };
  // A worker process ended with `status`; a busy one takes its shard with it.
  auto reaped = [&](pid_t pid, int status) {
    Running r = running[pid];
    running.erase(pid);
    const auto now = Clock::now();
    busy_s += std::chrono::duration<double>(now - r.spawned).count();
    // A server may have finished its shard and ended before its reply was read: the shard is
    // done (its file is committed before the reply), whatever the exit status says.
    bool replied = false;
    for (const std::string& id : read_replies(r)) replied |= r.busy && id == r.item.shard.id();
    const std::string words = last_words(r);
    ::close(r.message_fd);
    if (r.command_fd >= 0) ::close(r.command_fd);
    if (!r.busy) return;
    const double item_s = std::chrono::duration<double>(now - r.started).count();
    const std::string written = recovery.records_dir(r.item) + "/" + r.item.shard.id() +
                                records_extension(exp.records_format);
    const std::string log = "; log: " + log_path(dir, r.item);
    if (replied || (WIFEXITED(status) && WEXITSTATUS(status) == 0 && fs::exists(written))) {
      succeeded(r, item_s);
    } else if (WIFSIGNALED(status)) {  // the driver crashed: re-run, then bisect
      conclude(r, WorkOutcome::kCrash, describe_exit_status(status) + log);
    } else if (words.find(kDriverMismatch) != std::string::npos) {
      // A worker that loaded another driver than the run's: nothing of this run may be drawn here.
      ++finished;
      result.failures.push_back({r.item.shard.id(), describe_exit_status(status) + ": " + words + log});
      if (result.wrong_renderer.empty()) result.wrong_renderer = words;
    } else {  // an error the worker reported (I/O, bad input): no primitive to blame
      ++finished;
      const std::string why = describe_exit_status(status) + (words.empty() ? "" : ": " + words);
      std::fprintf(stderr, "%srenderaudit: shard %s: worker %s\n", show ? "\n" : "",
                   r.item.shard.id().c_str(), why.c_str());
      result.failures.push_back({r.item.shard.id(), why + log});
    }
  };
  // SIGPIPE ignored: a server that died before reading its command fails the write instead.
  struct sigaction ignore_pipe {}, old_pipe {};
  ignore_pipe.sa_handler = SIG_IGN;
  sigemptyset(&ignore_pipe.sa_mask);
  sigaction(SIGPIPE, &ignore_pipe, &old_pipe);
  while (!todo.empty() || !running.empty()) {
    if (g_interrupted) {
      result.interrupted = true;
      break;  // the reaper kills the workers
    }
    if (const std::string wrong = renderer_check.mismatch(); !wrong.empty()) {
      todo.clear();
      result.wrong_renderer = wrong;
      break;
    }
    if (!result.wrong_renderer.empty()) {  // a worker's driver mismatch
      todo.clear();
      break;
    }
    // Idle servers take the next shard of their platform, or are told to end (end of input).
    for (auto& [pid, r] : running) {
      if (r.busy || r.command_fd < 0) continue;
      const auto it = next_for_server(r.item.shard.platform);
      if (it != todo.end()) {
        r.item = *it;
        todo.erase(it);
        r.busy = true;
        r.started = Clock::now();
        if (!send_command(r, dir, r.item, recovery.records_dir(r.item))) {
          ::close(r.command_fd);  // gone: its exit concludes the shard (a crash, or words)
          r.command_fd = -1;
        }
      } else {
        ::close(r.command_fd);
        r.command_fd = -1;
        r.told_to_end = Clock::now();
      }
    }
    while (!todo.empty() && int(running.size()) < jobs) {
      const WorkItem w = todo.front();
      todo.pop_front();
      Running r;
      r.item = w;
      r.started = r.spawned = Clock::now();
      if (servable(w)) {
        const Child child = spawn_server(program, dir, w);
        r.server = true, r.message_fd = child.message_fd, r.command_fd = child.command_fd;
        if (!send_command(r, dir, w, recovery.records_dir(w))) {
          ::close(r.command_fd);
          r.command_fd = -1;
        }
        running[child.pid] = r;
      } else {
        const Child child = spawn_worker(program, dir, w, recovery.records_dir(w));
        r.message_fd = child.message_fd;
        running[child.pid] = r;
      }
      ++result.worker_processes;
    }
    // Servers' replies: the shard is done, the server idle until the next pass.
    for (auto& [pid, r] : running) {
      if (!r.server) continue;
      for (const std::string& id : read_replies(r)) {
        if (!r.busy || id != r.item.shard.id()) continue;  // cannot happen: one shard at a time
        r.busy = false;
        succeeded(r, std::chrono::duration<double>(Clock::now() - r.started).count());
      }
    }
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, WNOHANG);
    if (pid > 0 && running.count(pid)) {
      reaped(pid, status);
      continue;  // reap everything that is ready before sleeping
    }
    const auto now = Clock::now();
    for (auto& [p, r] : running) {
      if (r.busy && std::chrono::duration<double>(now - r.started).count() > r.item.timeout_s) {
        ::kill(-p, SIGKILL);
        wait_child(p);
        Running timed_out = r;
        busy_s += std::chrono::duration<double>(now - timed_out.spawned).count();
        bool replied = false;
        for (const std::string& id : read_replies(timed_out))
          replied |= id == timed_out.item.shard.id();
        ::close(timed_out.message_fd);
        if (timed_out.command_fd >= 0) ::close(timed_out.command_fd);
        running.erase(p);
        char limit[32];
        std::snprintf(limit, sizeof limit, "%g", timed_out.item.timeout_s);
        const std::string written =
            recovery.records_dir(timed_out.item) + "/" + timed_out.item.shard.id() +
            records_extension(exp.records_format);
        if (replied || fs::exists(written)) {  // it hung after committing its records: teardown
          std::fprintf(stderr, "%srenderaudit: shard %s: its worker hung after writing every "
                       "record (killed after %s s; the shard is complete; log: %s)\n",
                       show ? "\n" : "", timed_out.item.shard.id().c_str(), limit,
                       log_path(dir, timed_out.item).c_str());
          succeeded(timed_out, std::chrono::duration<double>(now - timed_out.started).count());
          break;
        }
        conclude(timed_out, WorkOutcome::kTimeout,
                 std::string("timed out after ") + limit + " s (killed)");
        break;
      }
      const double grace_s = std::min(kServerExitGraceS, r.item.timeout_s);
      if (r.server && !r.busy && r.command_fd < 0 &&
          std::chrono::duration<double>(now - r.told_to_end).count() > grace_s) {
        ::kill(-p, SIGKILL);  // every shard it ran is committed: nothing is lost
        wait_child(p);
        busy_s += std::chrono::duration<double>(now - r.spawned).count();
        std::fprintf(stderr, "%srenderaudit: a %s worker did not exit within %g s of its last "
                     "shard (killed; its shards are complete; log: %s)\n", show ? "\n" : "",
                     r.item.shard.platform.c_str(), grace_s, log_path(dir, r.item).c_str());
        ::close(r.message_fd);
        running.erase(p);
        break;
      }
    }
    if (now - last_progress_file > std::chrono::seconds(2)) {
      last_progress_file = now;
      progress_now(false);
    }
    if (show && now - last_progress > std::chrono::milliseconds(250)) {
      last_progress = now;
      const double elapsed = std::chrono::duration<double>(now - t_start).count();
      const double rate = primitives_done / std::max(elapsed, 1e-9);
      std::fprintf(stderr, "\r[%zu/%zu shards] %llu primitives, %.0f/s, %zu failed, left %s   ",
                   finished, shards_to_run, static_cast<unsigned long long>(primitives_done), rate,
                   result.failures.size(),
                   duration_text(cost_done > 0 ? seconds_left(elapsed) : NAN).c_str());
    }
    // Sleep up to 5 ms, waking at once when a server replies (the next shard is sent at once).
    std::vector<pollfd> replies;
    for (const auto& [p, r] : running)
      if (r.server && r.busy) replies.push_back({r.message_fd, POLLIN, 0});
    ::poll(replies.data(), replies.size(), 5);
  }
  if (show) std::fprintf(stderr, "\n");
  reaper.stop_all();  // no worker runs past this point
  progress_now(true);
  fs::remove_all(ShardRecovery::parts_dir(dir));
  remove_temporaries(dir);  // what killed (timed-out) workers left half-written
  sigaction(SIGINT, &old_int, nullptr);
  sigaction(SIGTERM, &old_term, nullptr);
  sigaction(SIGHUP, &old_hup, nullptr);
  sigaction(SIGPIPE, &old_pipe, nullptr);

  manifest["drivers"] = drivers_json(dir);
  manifest["finished"] = utc_now_iso8601();
  const double elapsed_s = std::chrono::duration<double>(Clock::now() - t_start).count();
  manifest["invocations"].back()["elapsed_s"] = elapsed_s;
  // How well the cores were used: worker-seconds, and the core-seconds no worker used (the tail
  // when the last shards run alone, plus the coordinator's own gaps)
  manifest["invocations"].back()["shard_order"] =
      options.shard_order == RunOptions::ShardOrder::kPlan ? "plan" : "largest-expected-cost-first";
  manifest["invocations"].back()["worker_busy_s"] = busy_s;
  manifest["invocations"].back()["worker_processes"] = result.worker_processes;
  manifest["invocations"].back()["workers"] = options.serve_shards ? "serve-shards" : "per-shard";
  manifest["invocations"].back()["idle_core_s"] = std::max(0.0, jobs * elapsed_s - busy_s);
  manifest["shard_seconds"] = shard_seconds;
  size_t complete = 0;
  for (const Shard& s : all) complete += fs::exists(s.records_path(dir));
  manifest["shards"] = {{"total", all.size()}, {"complete", complete}};
  nlohmann::json failures = nlohmann::json::array();
  for (const auto& f : result.failures) failures.push_back({{"shard", f.shard}, {"reason", f.reason}});
  manifest["failures"] = failures;
  if (!result.damaged.empty()) {
    nlohmann::json damaged = manifest.value("damaged_shards_redone", nlohmann::json::array());
    for (const auto& d : result.damaged) damaged.push_back({{"shard", d.shard}, {"reason", d.reason}});
    manifest["damaged_shards_redone"] = damaged;
  }
  result.failed_primitives = recovery.failed_primitives();
  // What the records hold, whoever wrote them (an earlier invocation, a merge), with the reasons
  // this invocation and the manifest before it gave.
  std::map<std::string, std::string> reasons;
  add_failure_reasons(manifest.value("failed_primitives", nlohmann::json::array()), &reasons);
  for (const FailedPrimitive& f : result.failed_primitives)
    reasons[failure_key(f.shard, f.index)] = f.reason;
  result.failed_primitives_held = failed_primitives_in_records(dir, all, reasons);
  nlohmann::json failed = nlohmann::json::array();
  for (const FailedPrimitive& f : result.failed_primitives_held)
    failed.push_back({{"shard", f.shard}, {"index", f.index}, {"status", status_name(f.status)},
                      {"reason", f.reason}});
  manifest["failed_primitives"] = failed;
  result.shards_complete = complete;
  if (!result.wrong_renderer.empty()) manifest["wrong_renderer"] = result.wrong_renderer;
  manifest["status"] = result.interrupted                 ? "interrupted"
                       : !result.wrong_renderer.empty()   ? "wrong-renderer"
                       : complete != all.size()           ? "failed"
                       : !failed.empty()                  ? "complete-with-failed-primitives"
                                                          : "complete";
  write_manifest(manifest_path, manifest);
  return result;
}

}  // namespace ra
