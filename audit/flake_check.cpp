#include "audit/flake_check.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <thread>

#include "rundir/records_reader.h"
#include "rundir/run_folder.h"
#include "util/atomic_file.h"
#include "util/child_process.h"
#include "rundir/experiment.h"
#include "rundir/run_experiment.h"
#include "rundir/shard.h"
#include "util/worker_program.h"
#include "rundir/platform_spec.h"
#include "rundir/shard_records.h"
#include "util/errors.h"

namespace fs = std::filesystem;

namespace ra::audit {
namespace {

using Clock = std::chrono::steady_clock;

rundir::Shard shard_of(const RerenderBatch& b) {
  return {b.platform, b.kind, b.view, b.begin, b.end};
}

// A re-render worker: its own process group (a timeout kills all it started), dying with us, its
// output in its log, RA_RENDER_ATTEMPT set to `attempt`.
pid_t spawn(const std::string& program, const std::string& dir, const RerenderBatch& b,
            int attempt) {
  util::ChildSpec spec;
  spec.argv = {program,
               "worker",
               dir,
               b.platform,
               geometry::kind_name(b.kind),
               std::to_string(b.view),
               std::to_string(b.begin),
               std::to_string(b.end)};
  spec.set_env = {"RA_RENDER_ATTEMPT=" + std::to_string(attempt)};
  spec.log_to(rundir::run_folder::shard_log(dir, shard_of(b).id()));
  spec.stdin_null = true;
  spec.own_process_group = true;
  return util::start_child(spec).pid;
}

// The last non-empty line of a child's log, for the error message (the directory is removed).
std::string last_log_line(const std::string& path) {
  std::ifstream in(path);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  return last;
}

}  // namespace

void KnownFailures::add(const std::string& platform, geometry::Kind kind, int view, uint64_t begin,
                        uint64_t end) {
  ranges[{platform, int(kind), view}].push_back({begin, end});
}

bool KnownFailures::hits(const std::string& platform, geometry::Kind kind, int view, uint64_t begin,
                         uint64_t end) const {
  const auto it = ranges.find({platform, int(kind), view});
  if (it == ranges.end()) return false;
  for (const auto& [b, e] : it->second)
    if (b < end && begin < e) return true;
  return false;
}

std::vector<RerenderBatch> plan_rerender(std::vector<RerenderRequest> requests,
                                         const KnownFailures& avoid, uint64_t max_gap) {
  auto key = [](const RerenderRequest& r) { return std::tie(r.platform, r.kind, r.view, r.index); };
  std::sort(requests.begin(), requests.end(),
            [&](const RerenderRequest& a, const RerenderRequest& b) { return key(a) < key(b); });
  requests.erase(std::unique(requests.begin(), requests.end(),
                             [&](const RerenderRequest& a, const RerenderRequest& b) {
                               return key(a) == key(b);
                             }),
                 requests.end());
  std::vector<RerenderBatch> out;
  for (const RerenderRequest& r : requests) {
    if (!out.empty()) {
      RerenderBatch& last = out.back();
      // Extend the open range over the gap [last.end, r.index) when it is short and safe.
      if (last.platform == r.platform && last.kind == r.kind && last.view == r.view &&
          r.index - last.end < max_gap &&
          !avoid.hits(r.platform, r.kind, r.view, last.end, r.index)) {
        last.end = r.index + 1;
        continue;
      }
    }
    out.push_back({r.platform, r.kind, r.view, r.index, r.index + 1, ""});
  }
  return out;
}

RerenderResult rerender(const std::vector<RerenderBatch>& batches, const RerenderOptions& options) {
  RerenderResult result;
  result.batches = batches;
  if (batches.empty()) return result;
  const rundir::Experiment exp =
      options.experiment_text.empty()
          ? rundir::load_run_experiment(options.run_dir)
          : rundir::parse_experiment(options.experiment_text,
                                     rundir::run_folder::experiment(options.run_dir));
  const double timeout_s = options.timeout_s > 0 ? options.timeout_s : exp.shard_timeout_s;
  const std::string program = options.program.empty() ? util::worker_program() : options.program;
  const unsigned jobs =
      options.jobs > 0 ? options.jobs : std::max(1u, std::thread::hardware_concurrency());

  // A private run directory: the experiment, and the folders a worker writes into.
  std::string templ = (fs::temp_directory_path() / "renderaudit-flake-XXXXXX").string();
  if (!::mkdtemp(templ.data()))
    throw std::runtime_error("cannot create a temporary directory for the flake check: " +
                             std::string(std::strerror(errno)));
  const std::string dir = templ;
  for (const std::string& folder :
       {rundir::run_folder::records(dir), rundir::run_folder::drivers(dir),
        rundir::run_folder::logs(dir)})
    fs::create_directories(folder);
  util::write_file_atomic(rundir::run_folder::experiment(dir), exp.text);
  // The run's driver files: each re-render worker checks the driver it loaded against them
  // (platforms/renderer_check.h) and stops rather than draw with another.
  std::error_code copy_ec;
  for (const auto& e :
       fs::directory_iterator(rundir::run_folder::drivers(options.run_dir), copy_ec))
    if (options.copy_driver_files && e.path().extension() == ".json")
      fs::copy_file(e.path(), rundir::run_folder::drivers(dir) + "/" + e.path().filename().string(),
                    copy_ec);

  struct Running {
    std::size_t batch;
    Clock::time_point started;
  };
  std::vector<std::pair<pid_t, Running>> running;
  const auto t0 = Clock::now();
  std::size_t next = 0;
  auto finish = [&](std::size_t b, const std::string& error) {
    RerenderBatch& batch = result.batches[b];
    const rundir::Shard s = shard_of(batch);
    const std::string log = last_log_line(rundir::run_folder::shard_log(dir, s.id()));
    batch.error = error.empty() || log.empty() ? error : error + ": " + log;
    if (!batch.error.empty()) return;
    // the re-render's own file, judged by the seal rule as any reader judges records
    rundir::ShardRecordsFile file;
    try {
      file = rundir::find_shard_records(dir, s);
    } catch (const util::UserError& e) {
      batch.error = e.what();
      return;
    }
    if (file.path.empty() || !file.damage.empty()) {
      batch.error = file.path.empty() ? "wrote no records" : file.path + ": damaged: " + file.damage;
      return;
    }
    rundir::read_records(file.path, [&](const metrics::Record& r) {
      result.hashes[{batch.platform, int(batch.kind), batch.view, r.index}] = r.pixel_hash;
      result.pixels[{batch.platform, int(batch.kind), batch.view, r.index}] = r.pixels;
    });
  };
  try {
    while (next < result.batches.size() || !running.empty()) {
      while (next < result.batches.size() && running.size() < jobs) {
        running.push_back({spawn(program, dir, result.batches[next], options.attempt), {next, Clock::now()}});
        ++next;
      }
      bool reaped = false;
      for (std::size_t i = 0; i < running.size(); ++i) {
        const auto [pid, r] = running[i];
        int status = 0;
        if (::waitpid(pid, &status, WNOHANG) == pid) {
          const bool ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
          finish(r.batch, ok ? "" : util::describe_exit_status(status));
        } else if (std::chrono::duration<double>(Clock::now() - r.started).count() > timeout_s) {
          ::kill(-pid, SIGKILL);
          ::waitpid(pid, nullptr, 0);
          finish(r.batch, "timed out after " + std::to_string(int(timeout_s)) + " s (killed)");
        } else {
          continue;
        }
        running.erase(running.begin() + long(i--));
        reaped = true;
      }
      if (!reaped) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  } catch (...) {
    for (const auto& [pid, r] : running) ::kill(-pid, SIGKILL), ::waitpid(pid, nullptr, 0);
    fs::remove_all(dir);
    throw;
  }
  result.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  std::error_code ec;
  fs::remove_all(dir, ec);
  return result;
}

FlakeCheckSummary apply_flake_check(audit::PrimitiveComparison& comparison,
                                    const std::vector<audit::PlatformPair>& pairs, bool between,
                                    const KnownFailures& avoid, std::size_t cap,
                                    const RerenderOptions& options) {
  FlakeCheckSummary s;
  s.performed = cap > 0;
  s.both_sides = between;
  s.cap = cap;
  const std::size_t n = std::min(cap, comparison.changed.size());
  s.checked = n;
  s.not_checked = comparison.changed.size() - n;
  if (n == 0) return s;

  std::vector<RerenderRequest> requests;
  for (std::size_t i = 0; i < n; ++i) {
    const audit::ChangedPrimitive& c = comparison.changed[i];
    requests.push_back({pairs[c.pair].current, c.kind, c.view, c.index});
    if (between) requests.push_back({pairs[c.pair].baseline, c.kind, c.view, c.index});
  }
  const RerenderResult r = rerender(plan_rerender(requests, avoid, options.max_gap), options);
  s.processes = r.batches.size();
  s.seconds = r.seconds;
  for (const RerenderBatch& b : r.batches) {
    // A re-render on another driver than the run's is no evidence either way: stop the audit.
    if (b.error.find(rundir::kDriverMismatch) != std::string::npos)
      throw util::UserError("the flake check cannot re-render " + b.platform +
                            " with the driver that "
                            "made " +
                            options.run_dir + ": " +
                            b.error.substr(b.error.find(rundir::kDriverMismatch)));
    if (!b.error.empty()) s.failed_batches.push_back(b);
  }

  for (std::size_t i = 0; i < n; ++i) {
    audit::ChangedPrimitive& c = comparison.changed[i];
    const auto now = r.hashes.find({pairs[c.pair].current, int(c.kind), c.view, c.index});
    const auto base = r.hashes.find({pairs[c.pair].baseline, int(c.kind), c.view, c.index});
    if (now == r.hashes.end() || (between && base == r.hashes.end())) {
      c.recheck = audit::Recheck::kRerenderFailed;
      ++s.rerender_failed;
      continue;
    }
    c.rerender_hash = now->second;
    if (c.before.pixel_hash == c.after.pixel_hash) {  // status or class changed, not the pixels:
      c.recheck = audit::Recheck::kStillDifferent;           // pixels alone cannot clear it
      ++s.still_different;
      continue;
    }
    const uint64_t reference = between ? base->second : c.before.pixel_hash;
    c.recheck = c.rerender_hash == reference ? audit::Recheck::kFlake : audit::Recheck::kStillDifferent;
    ++(c.recheck == audit::Recheck::kFlake ? s.flakes : s.still_different);
  }
  return s;
}

}  // namespace ra::audit
