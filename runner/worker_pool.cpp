// The worker processes of a run (see the header).
#include "runner/worker_pool.h"

#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <filesystem>

#include "rundir/platform_spec.h"
#include "rundir/run_folder.h"
#include "runner/shard_server.h"
#include "util/child_process.h"
#include "util/number_text.h"

namespace fs = std::filesystem;

namespace ra::runner {
namespace {

// A path as a child's argument: absolute, so that a folder named "-x" is never read as an option.
std::string as_argument(const std::string& path) {
  std::error_code ec;
  const std::filesystem::path p = std::filesystem::absolute(path, ec);
  return ec ? path : p.string();
}

// Reads what the worker said since last time: the ids of the shards it reports done (a server's
// replies), in order; anything else is kept as its last words.
template <typename Running>
std::vector<std::string> read_replies(Running& r) {
  r.unread += util::drain_fd(r.message_fd);
  std::vector<std::string> done;
  size_t start = 0;
  for (size_t nl; (nl = r.unread.find('\n', start)) != std::string::npos; start = nl + 1) {
    const std::string line = r.unread.substr(start, nl - start);
    std::string id;
    if (rundir::parse_shard_done(line, &id))
      done.push_back(id);
    else
      r.words += line + "\n";
  }
  r.unread.erase(0, start);
  return done;
}

// What a finished worker said that was not a reply (the error it stopped on), one line.
template <typename Running>
std::string last_words(Running& r) {
  read_replies(r);
  std::string text = r.words + r.unread;
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text;
}

WorkerEvent event(WorkerEvent::Kind kind, const WorkItem& item) {
  WorkerEvent e;
  e.kind = kind;
  e.item = item;
  return e;
}

double seconds_between(std::chrono::steady_clock::time_point a,
                       std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

}  // namespace

WorkerPool::WorkerPool(Settings settings, RecordsDirOf records_dir, OnEvent on_event)
    : settings_(std::move(settings)),
      records_dir_(std::move(records_dir)),
      on_event_(std::move(on_event)) {}

WorkerPool::~WorkerPool() { stop_all(); }

void WorkerPool::stop_all() {
  for (auto& [pid, r] : running_) ::kill(-pid, SIGKILL);
  for (auto& [pid, r] : running_) {
    util::wait_child(pid);
    if (r.message_fd >= 0) ::close(r.message_fd);
    if (r.command_fd >= 0) ::close(r.command_fd);
  }
  running_.clear();
}

std::vector<std::string> WorkerPool::busy_shards() const {
  std::vector<std::string> ids;
  for (const auto& [pid, r] : running_)
    if (r.busy) ids.push_back(r.item.shard.id());  // not a server between shards
  return ids;
}

std::string WorkerPool::log_path(const WorkItem& item) const {
  return rundir::run_folder::shard_log(settings_.dir, item.shard.id(), item.attempt > 1);
}

// A shard a server may take: a whole one at its first attempt (re-runs and bisection parts get
// processes of their own, whose crash names them alone).
bool WorkerPool::servable(const WorkItem& w) const {
  return settings_.serve_shards && w.attempt == 1 && !w.is_part();
}

// The next shard for an idle server of `platform`: the first of its platform among the next
// 4 x jobs in the queue, which would start soon anyway (a shard of another platform waits for at
// most that many); none: the server ends, and the queue's order (largest cost first) is kept. A
// window of jobs: the short bench run started 16 processes, of 4 x jobs: 8.
std::deque<WorkItem>::iterator WorkerPool::next_for_server(std::deque<WorkItem>& todo,
                                                           const std::string& platform) {
  auto it = todo.begin();
  for (int k = 0; k < 4 * settings_.jobs && it != todo.end(); ++k, ++it)
    if (it->shard.platform == platform && servable(*it)) return it;
  return todo.end();
}

// Sends `item` to a server; false when it is gone (it will be reaped as such).
bool WorkerPool::send_command(Running& r, const WorkItem& item) {
  const std::string line =
      rundir::shard_command_line({item.shard, records_dir_(item), log_path(item)}) + "\n";
  size_t done = 0;
  while (done < line.size()) {
    const ssize_t n = ::write(r.command_fd, line.data() + done, line.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += size_t(n);
  }
  return true;
}

bool WorkerPool::serve(std::deque<WorkItem>& todo) {
  feed_idle_servers(todo);
  start_workers(todo);
  read_server_replies();
  int status = 0;
  const pid_t pid = ::waitpid(-1, &status, WNOHANG);
  if (pid > 0 && running_.count(pid)) {
    reaped(pid, status);
    return true;
  }
  return false;
}

// Idle servers take the next shard of their platform, or are told to end (end of input).
void WorkerPool::feed_idle_servers(std::deque<WorkItem>& todo) {
  for (auto& [pid, r] : running_) {
    if (r.busy || r.command_fd < 0) continue;
    const auto it = next_for_server(todo, r.item.shard.platform);
    if (it != todo.end()) {
      r.item = *it;
      todo.erase(it);
      r.busy = true;
      r.started = Clock::now();
      if (!send_command(r, r.item)) {
        ::close(r.command_fd);  // gone: its exit concludes the shard (a crash, or words)
        r.command_fd = -1;
      }
    } else {
      ::close(r.command_fd);
      r.command_fd = -1;
      r.told_to_end = Clock::now();
    }
  }
}

// A worker: its own process group (a timeout kills all it started), dies with this process, its
// output in its log, and a message pipe for its last words (they reach us even when the disk of
// the log is full). A server is set up the same way, with its commands on its stdin.
void WorkerPool::start_workers(std::deque<WorkItem>& todo) {
  while (!todo.empty() && int(running_.size()) < settings_.jobs) {
    const WorkItem w = todo.front();
    todo.pop_front();
    Running r;
    r.item = w;
    r.started = r.spawned = Clock::now();
    util::ChildSpec spec;
    const rundir::Shard& s = w.shard;
    spec.own_process_group = true;
    spec.message_pipe = true;
    spec.log_to(log_path(w));  // a server's: until the first command names it again
    if (servable(w)) {
      spec.argv = {settings_.program, "serve-shards", as_argument(settings_.dir), s.platform};
      spec.set_env = {"RA_RENDER_ATTEMPT=1"};
      spec.command_pipe = true;
      const util::Child child = util::start_child(spec);
      r.server = true, r.message_fd = child.message_fd, r.command_fd = child.command_fd;
      if (!send_command(r, w)) {
        ::close(r.command_fd);
        r.command_fd = -1;
      }
      running_[child.pid] = r;
    } else {
      spec.argv = {settings_.program,
                   "worker",
                   as_argument(settings_.dir),
                   s.platform,
                   geometry::kind_name(s.kind),
                   std::to_string(s.view),
                   std::to_string(s.begin),
                   std::to_string(s.end),
                   "--records-dir",
                   as_argument(records_dir_(w))};
      spec.set_env = {"RA_RENDER_ATTEMPT=" + std::to_string(w.attempt)};
      spec.stdin_null = true;
      const util::Child child = util::start_child(spec);
      r.message_fd = child.message_fd;
      running_[child.pid] = r;
    }
    ++processes_;
  }
}

// Servers' replies: the shard is done, the server idle until the next pass.
void WorkerPool::read_server_replies() {
  for (auto& [pid, r] : running_) {
    if (!r.server) continue;
    for (const std::string& id : read_replies(r)) {
      if (!r.busy || id != r.item.shard.id()) continue;  // cannot happen: one shard at a time
      r.busy = false;
      WorkerEvent e = event(WorkerEvent::Kind::kSucceeded, r.item);
      e.item_s = seconds_between(r.started, Clock::now());
      on_event_(e);
    }
  }
}

// A worker process ended with `status`; a busy one takes its item with it.
void WorkerPool::reaped(pid_t pid, int status) {
  Running r = running_[pid];
  running_.erase(pid);
  const auto now = Clock::now();
  busy_s_ += seconds_between(r.spawned, now);
  // A server may have finished its shard and ended before its reply was read: the shard is done
  // (its file is committed before the reply), whatever the exit status says.
  bool replied = false;
  for (const std::string& id : read_replies(r)) replied |= r.busy && id == r.item.shard.id();
  const std::string words = last_words(r);
  ::close(r.message_fd);
  if (r.command_fd >= 0) ::close(r.command_fd);
  if (!r.busy) return;
  WorkerEvent e = event(WorkerEvent::Kind::kSucceeded, r.item);
  e.item_s = seconds_between(r.started, now);
  e.log = "; log: " + log_path(r.item);
  const std::string written = records_dir_(r.item) + "/" + r.item.shard.id() + settings_.records_extension;
  if (replied || (WIFEXITED(status) && WEXITSTATUS(status) == 0 && fs::exists(written))) {
    e.kind = WorkerEvent::Kind::kSucceeded;
  } else if (WIFSIGNALED(status)) {  // the driver crashed: re-run, then bisect
    e.kind = WorkerEvent::Kind::kCrashed;
    e.reason = util::describe_exit_status(status) + e.log;
  } else {
    // A worker that loaded another driver than the run's: nothing of this run may be drawn here.
    e.kind = words.find(rundir::kDriverMismatch) != std::string::npos
                 ? WorkerEvent::Kind::kDriverMismatch
                 : WorkerEvent::Kind::kFailed;
    e.reason = util::describe_exit_status(status);
    e.words = words;
  }
  on_event_(e);
}

void WorkerPool::enforce_time_limits() {
  const auto now = Clock::now();
  for (auto& [p, r] : running_) {
    if (r.busy && seconds_between(r.started, now) > r.item.timeout_s) {
      timed_out(p, now);
      return;
    }
    const double grace_s = std::min(kServerExitGraceS, r.item.timeout_s);
    if (r.server && !r.busy && r.command_fd < 0 && seconds_between(r.told_to_end, now) > grace_s) {
      ::kill(-p, SIGKILL);  // every shard it ran is committed: nothing is lost
      util::wait_child(p);
      busy_s_ += seconds_between(r.spawned, now);
      std::fprintf(stderr, "%srenderaudit: a %s worker did not exit within %g s of its last "
                   "shard (killed; its shards are complete; log: %s)\n", line_break(),
                   r.item.shard.platform.c_str(), grace_s, log_path(r.item).c_str());
      ::close(r.message_fd);
      running_.erase(p);
      return;
    }
  }
}

// Kills the busy worker `pid` that passed its item's time limit; the item is complete when its
// records were committed before it hung (in its driver's teardown, typically).
void WorkerPool::timed_out(pid_t pid, Clock::time_point now) {
  ::kill(-pid, SIGKILL);
  util::wait_child(pid);
  Running r = running_[pid];
  running_.erase(pid);
  busy_s_ += seconds_between(r.spawned, now);
  bool replied = false;
  for (const std::string& id : read_replies(r)) replied |= id == r.item.shard.id();
  ::close(r.message_fd);
  if (r.command_fd >= 0) ::close(r.command_fd);
  const std::string limit = util::significant(r.item.timeout_s, 6);
  const std::string written = records_dir_(r.item) + "/" + r.item.shard.id() + settings_.records_extension;
  WorkerEvent e = event(WorkerEvent::Kind::kTimedOut, r.item);
  e.item_s = seconds_between(r.started, now);
  e.log = "; log: " + log_path(r.item);
  if (replied || fs::exists(written)) {
    std::fprintf(stderr, "%srenderaudit: shard %s: its worker hung after writing every record "
                 "(killed after %s s; the shard is complete; log: %s)\n",
                 line_break(), r.item.shard.id().c_str(), limit.c_str(), log_path(r.item).c_str());
    e.kind = WorkerEvent::Kind::kSucceeded;
  } else {
    e.reason = std::string("timed out after ") + limit + " s (killed)";
  }
  on_event_(e);
}

void WorkerPool::wait(int ms) {
  std::vector<pollfd> replies;
  for (const auto& [p, r] : running_)
    if (r.server && r.busy) replies.push_back({r.message_fd, POLLIN, 0});
  ::poll(replies.data(), replies.size(), ms);
}

}  // namespace ra::runner
