// How far a run's invocation is (see the header).
#include "runner/progress_meter.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "rundir/manifest.h"
#include "runner/run_progress.h"
#include "util/duration_text.h"
#include "util/number_text.h"

namespace ra::runner {

ProgressMeter::ProgressMeter(const rundir::Experiment& exp, const std::deque<WorkItem>& todo)
    : exp_(exp) {
  shards_to_run_ = todo.size();
  for (const WorkItem& w : todo) {
    primitives_todo_ += w.shard.size();
    cost_todo_ += expected_cost_of(w.shard, exp_);
  }
}

void ProgressMeter::item_done(const WorkItem& w) {
  primitives_done_ += w.shard.size();
  cost_done_ += expected_cost_of(w.shard, exp_);
}

double ProgressMeter::elapsed_s() const {
  return std::chrono::duration<double>(Clock::now() - start_).count();
}

double ProgressMeter::seconds_left(double elapsed_s) const {
  if (cost_done_ <= 0) return -1.0;
  return elapsed_s * std::max(0.0, cost_todo_ - cost_done_) / cost_done_;
}

void ProgressMeter::write_file(const std::string& dir, const std::string& host,
                               const WorkerPool& pool, const std::vector<ShardFailure>& failures,
                               bool at_end) {
  const auto now = Clock::now();
  if (!at_end && now - last_file_ <= std::chrono::seconds(2)) return;
  last_file_ = now;
  RunProgress p;
  p.host = host;
  p.pid = ::getpid();
  p.updated_utc = rundir::utc_now_iso8601();
  p.shards_to_run = shards_to_run_;
  p.shards_finished = finished_;
  p.running = pool.busy_shards();
  for (const auto& f : failures) p.failed.push_back(f.shard);
  p.primitives_done = primitives_done_;
  p.primitives_todo = primitives_todo_;
  p.elapsed_s = elapsed_s();
  p.left_s = seconds_left(p.elapsed_s);
  if (at_end) p.finished = true, p.left_s = 0;
  write_run_progress(dir, p);
}

void ProgressMeter::show(std::size_t failed) {
  if (line_.terminal())
    show_line(failed);
  else
    log_line(failed);
}

void ProgressMeter::show_line(std::size_t failed) {
  const auto now = Clock::now();
  if (now - last_line_ <= std::chrono::milliseconds(250)) return;
  last_line_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = primitives_done_ / std::max(elapsed, 1e-9);
  line_.show(util::format_text(
      "[%zu/%zu shards] %llu primitives, %.0f/s, %zu failed, left %s", finished_, shards_to_run_,
      primitives_done_, rate, failed,
      util::duration_text(cost_done_ > 0 ? seconds_left(elapsed) : NAN).c_str()));
}

void ProgressMeter::log_line(std::size_t failed) {
  const auto now = Clock::now();
  if (now - last_log_ < std::chrono::seconds(30)) return;
  const int tenths = cost_todo_ > 0 ? int(10 * cost_done_ / cost_todo_) : 0;
  if (tenths >= 10) return;  // all done: the run's own last line follows
  if (tenths <= logged_tenths_ && now - last_log_ < std::chrono::minutes(5)) return;
  last_log_ = now;
  logged_tenths_ = tenths;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  line_.show(util::format_text(
      "run: %d%% done (%zu of %zu shards, %s primitives%s), %s so far, %s left",
      cost_todo_ > 0 ? int(100 * cost_done_ / cost_todo_) : 0, finished_, shards_to_run_,
      util::grouped(primitives_done_).c_str(),
      failed ? (", " + std::to_string(failed) + " failed").c_str() : "",
      util::elapsed_text(elapsed).c_str(),
      cost_done_ > 0 ? ("about " + util::elapsed_text(seconds_left(elapsed))).c_str()
                     : "time not known yet"));
}

}  // namespace ra::runner
