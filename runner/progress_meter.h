// How far a run's invocation is: shards and primitives done, and the time left, estimated in
// expected cost (rundir/shard_cost.h), not in primitives: the most expensive shards run first, so
// a rate in primitives per second would overestimate it. Shown on stderr (a progress line on a
// terminal, occasional whole lines elsewhere) and in DIR/progress.json for `renderaudit status` (runner/run_progress.h).
#pragma once

#include <chrono>
#include <deque>
#include <string>
#include <vector>

#include "rundir/experiment.h"
#include "runner/run_plan.h"
#include "runner/shard_recovery.h"
#include "runner/worker_pool.h"
#include "util/progress_line.h"

namespace ra::runner {

class ProgressMeter {
 public:
  // `todo`: what this invocation runs.
  ProgressMeter(const rundir::Experiment& exp, const std::deque<WorkItem>& todo);
  void item_done(const WorkItem& w);  // a shard or part whose records are committed
  void shard_finished() { ++finished_; }  // a whole shard ended, well or not
  std::size_t finished() const { return finished_; }
  double elapsed_s() const;  // wall seconds since the meter began
  // Seconds left at `elapsed_s`; negative while nothing is done.
  double seconds_left(double elapsed_s) const;
  // DIR/progress.json: every 2 s, and when `at_end`.
  void write_file(const std::string& dir, const std::string& host, const WorkerPool& pool,
                  const std::vector<ShardFailure>& failures, bool at_end);
  // Progress on stderr (util/progress_line.h): on a terminal the line rewritten every 250 ms;
  // elsewhere (a log, a pipe, CI) a whole line when another tenth of the expected cost is done,
  // at most every 30 s and at least every 5 minutes, so a short run prints none and a long one
  // about ten.
  void show(std::size_t failed);
  // Ends the terminal's progress line, so that what follows starts on a line of its own.
  void end_line() { line_.end(); }
  bool on_terminal() const { return line_.terminal(); }

 private:
  using Clock = std::chrono::steady_clock;
  void show_line(std::size_t failed);
  void log_line(std::size_t failed);

  const rundir::Experiment& exp_;
  util::ProgressLine line_;
  const Clock::time_point start_ = Clock::now();
  Clock::time_point last_line_ = start_ - std::chrono::seconds(1);
  Clock::time_point last_file_ = start_ - std::chrono::seconds(10);
  Clock::time_point last_log_ = start_;
  int logged_tenths_ = 0;  // tenths of the expected cost done at the last logged line
  std::size_t shards_to_run_ = 0, finished_ = 0;
  unsigned long long primitives_done_ = 0, primitives_todo_ = 0;
  double cost_todo_ = 0, cost_done_ = 0;
};

}  // namespace ra::runner
