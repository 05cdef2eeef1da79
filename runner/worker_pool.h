// The worker processes of a run: at most `jobs` at once, each a child of its own process group
// (util/child_process.h) that runs one shard (or part), or a server of one platform's whole shards
// (runner/shard_server.h) fed one shard at a time. The pool starts them, hands idle servers the
// next shard of their platform, reads their replies, reaps them, kills one that passes its item's
// time limit, and reports what became of each item as an event; what follows (a re-run, a
// bisection, a failure noted) is the caller's.
#pragma once

#include <chrono>
#include <deque>
#include <functional>
#include <map>
#include <string>
#include <sys/types.h>
#include <vector>

#include "runner/shard_recovery.h"

namespace ra::runner {

// What became of a worker's item.
struct WorkerEvent {
  enum class Kind {
    kSucceeded,       // its records are committed (its exit, a server's reply, or a hang after)
    kCrashed,         // killed by a signal: reason "crashed (signal 11, ...); log: PATH"
    kTimedOut,        // past item.timeout_s, killed: reason "timed out after 600 s (killed)"
    kDriverMismatch,  // it loaded another driver than the run's: nothing more may be drawn
    kFailed,          // an error the worker reported (I/O, bad input): no primitive to blame
  } kind = Kind::kSucceeded;
  WorkItem item;
  double item_s = 0;   // kSucceeded: wall seconds from the item's start to its end
  std::string reason;  // kCrashed, kTimedOut; kDriverMismatch, kFailed: the exit status
  std::string words;   // kDriverMismatch, kFailed: what the worker said last ("" if nothing)
  std::string log;     // "; log: PATH"
};

class WorkerPool {
 public:
  struct Settings {
    std::string program;        // the executable that runs `worker` and `serve-shards`
    std::string dir;            // the run directory (logs in DIR/logs)
    int jobs = 1;               // processes at once
    bool serve_shards = true;   // whole first-attempt shards go to servers
    bool progress_line = false; // a progress line is on stderr: messages start on a new line
    std::string records_extension = ".csv.zst";  // of a finished shard's file (".csv" plain)
  };
  using RecordsDirOf = std::function<std::string(const WorkItem&)>;
  using OnEvent = std::function<void(const WorkerEvent&)>;

  // `records_dir(item)`: where the worker for `item` writes; `on_event` is called as each item
  // ends, in the order they end.
  WorkerPool(Settings settings, RecordsDirOf records_dir, OnEvent on_event);
  ~WorkerPool();  // every exit path (an exception included) kills and reaps what still runs
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  // One pass: idle servers take the next shard of their platform from `todo` (or are told to
  // end), free slots start workers for the front of `todo`, servers' replies are read, one exited
  // worker is reaped. True when one was reaped: call again before sleeping.
  bool serve(std::deque<WorkItem>& todo);
  // Kills at most one worker past its item's time limit, or one server that did not exit within
  // its grace after being told to end.
  void enforce_time_limits();
  // Sleeps up to `ms` milliseconds, waking at once when a busy server replies.
  void wait(int ms);
  // Kills and reaps every worker (no event: what they ran is not concluded).
  void stop_all();

  bool empty() const { return running_.empty(); }
  std::vector<std::string> busy_shards() const;  // ids of the items being run now
  double busy_seconds() const { return busy_s_; }  // worker-seconds of every reaped worker
  std::size_t processes_started() const { return processes_; }

  // How long a server may take to exit once told that no shard is left: its shards are all
  // committed, so one that hangs in its driver's teardown is killed, and nothing is lost.
  static constexpr double kServerExitGraceS = 10;

 private:
  using Clock = std::chrono::steady_clock;
  // A worker process: one shard's (or part's), or a server of one platform's shards.
  struct Running {
    WorkItem item;                  // what it runs now (a server: valid while busy)
    bool busy = true;               // a server between shards is idle
    Clock::time_point started;      // when `item` started
    Clock::time_point spawned;      // when the process started
    int message_fd = -1;            // the worker's message pipe
    int command_fd = -1;            // a server's stdin; -1: a one-shard worker, or told to end
    bool server = false;
    std::string unread;             // message-pipe bytes not yet a whole line
    std::string words;              // what it said that is not a reply: its last words
    Clock::time_point told_to_end;  // a server: when its input was closed (no shard left)
  };

  bool servable(const WorkItem& w) const;
  std::deque<WorkItem>::iterator next_for_server(std::deque<WorkItem>& todo,
                                                 const std::string& platform);
  void feed_idle_servers(std::deque<WorkItem>& todo);
  void start_workers(std::deque<WorkItem>& todo);
  void read_server_replies();
  void reaped(pid_t pid, int status);
  void timed_out(pid_t pid, Clock::time_point now);
  bool send_command(Running& r, const WorkItem& item);
  std::string log_path(const WorkItem& item) const;
  const char* line_break() const { return settings_.progress_line ? "\n" : ""; }

  Settings settings_;
  RecordsDirOf records_dir_;
  OnEvent on_event_;
  std::map<pid_t, Running> running_;
  double busy_s_ = 0;
  std::size_t processes_ = 0;
};

}  // namespace ra::runner
