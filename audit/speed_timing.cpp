#include "audit/speed_timing.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <thread>

#include "rundir/experiment.h"
#include "rundir/records_reader.h"
#include "rundir/run_experiment.h"
#include "rundir/run_folder.h"
#include "rundir/shard.h"
#include "rundir/shard_command.h"
#include "rundir/shard_records.h"
#include "util/atomic_file.h"
#include "util/child_process.h"
#include "util/errors.h"
#include "util/worker_program.h"

namespace fs = std::filesystem;

namespace ra::audit {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// A private run folder for one side: its experiment, its run's driver files, records and logs.
std::string make_side_folder(const TimingSide& side, const std::string& experiment_text) {
  std::string templ = (fs::temp_directory_path() / "renderaudit-timing-XXXXXX").string();
  if (!::mkdtemp(templ.data()))
    throw std::runtime_error("cannot create a temporary folder for timing: " +
                             std::string(std::strerror(errno)));
  const std::string dir = templ;
  for (const std::string& folder : {rundir::run_folder::records(dir),
                                    rundir::run_folder::drivers(dir), rundir::run_folder::logs(dir)})
    fs::create_directories(folder);
  util::write_file_atomic(rundir::run_folder::experiment(dir), experiment_text);
  std::error_code ec;
  if (side.check_driver)
    for (const auto& e : fs::directory_iterator(rundir::run_folder::drivers(side.run_dir), ec))
      if (e.path().extension() == ".json")
        fs::copy_file(e.path(), rundir::run_folder::drivers(dir) + "/" + e.path().filename().string(),
                      ec);
  return dir;
}

std::string last_nonempty_line(const std::string& path) {
  std::ifstream in(path);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  return last;
}

// One process of one side: draws every range alone and returns "" or why it failed.
std::string draw_once(const std::string& program, const std::string& dir, const TimingSide& side,
                      const std::vector<TimingRange>& ranges, double timeout_s, SideTiming& out) {
  std::error_code ec;
  const std::string warmup = dir + "/warmup";
  for (const std::string& folder : {rundir::run_folder::records(dir), warmup}) {
    fs::remove_all(folder, ec);
    fs::create_directories(folder);
  }
  const std::string log = rundir::run_folder::logs(dir) + "/serve.log";
  util::ChildSpec spec;
  spec.argv = {program, "serve-shards", dir, side.platform, "--alone"};
  spec.log_to(log);
  spec.command_pipe = true;
  spec.own_process_group = true;
  const util::Child child = util::start_child(spec);
  // Each range twice, the first time untimed: a driver compiles its code for a state when it first
  // draws in it (llvmpipe's JIT took a third of the first primitives' time here), and only the
  // second pass measures the drawing itself. Every shard's output goes to the one log: the last
  // words of a failure are found there.
  std::string commands;
  for (const std::string& records : {warmup, rundir::run_folder::records(dir)})
    for (const TimingRange& r : ranges) {
      const rundir::Shard shard{side.platform, r.kind, r.view, r.begin, r.end};
      commands += rundir::shard_command_line({shard, records, log}) + "\n";
    }
  // A child that died early makes the write fail (EPIPE; SIGPIPE is ignored by the program):
  // its exit status says why below.
  for (std::size_t done = 0; done < commands.size();) {
    const ssize_t n = ::write(child.command_fd, commands.data() + done, commands.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += std::size_t(n);
  }
  ::close(child.command_fd);
  const auto started = Clock::now();
  int status = 0;
  for (;;) {
    const pid_t r = ::waitpid(child.pid, &status, WNOHANG);
    if (r == child.pid) break;
    if (r < 0 && errno != EINTR) return "cannot wait for the timing process";
    if (seconds_since(started) > timeout_s) {
      ::kill(-child.pid, SIGKILL);
      ::waitpid(child.pid, &status, 0);
      return "timed out after " + std::to_string(int(timeout_s)) + " s (killed)";
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (!(WIFEXITED(status) && WEXITSTATUS(status) == 0)) {
    const std::string last = last_nonempty_line(log);
    return util::describe_exit_status(status) + (last.empty() ? "" : ": " + last);
  }
  for (const TimingRange& r : ranges) {
    const rundir::Shard shard{side.platform, r.kind, r.view, r.begin, r.end};
    const rundir::ShardRecordsFile file = rundir::find_shard_records(dir, shard);
    if (file.path.empty()) return "wrote no records for " + shard.id();
    if (!file.damage.empty()) return file.path + ": damaged: " + file.damage;
    rundir::read_records(file.path, [&](const metrics::Record& rec) {
      if (rec.status != metrics::CaseStatus::kOk) return;
      const TimedKey key{int(r.kind), r.view, rec.index};
      out.render_us[key].push_back(rec.render_us);
      out.pixel_hash[key] = rec.pixel_hash;
    });
  }
  return "";
}

}  // namespace

std::vector<std::size_t> round_order(std::size_t sides, int round) {
  std::vector<std::size_t> order(sides);
  for (std::size_t i = 0; i < sides; ++i) order[i] = round % 2 == 0 ? i : sides - 1 - i;
  return order;
}

TimingResult time_interleaved(const std::vector<TimingSide>& sides,
                              const std::vector<TimingRange>& ranges, const TimingOptions& options,
                              const std::function<void(int, std::size_t, double)>& progress) {
  TimingResult result;
  result.sides.resize(sides.size());
  if (sides.empty() || ranges.empty() || options.repeats < 1) return result;
  const std::string program = options.program.empty() ? util::worker_program() : options.program;
  std::vector<std::string> folders;
  double timeout_s = options.timeout_s;
  for (const TimingSide& side : sides) {
    const rundir::Experiment exp =
        side.experiment_text.empty()
            ? rundir::load_run_experiment(side.run_dir)
            : rundir::parse_experiment(side.experiment_text,
                                       rundir::run_folder::experiment(side.run_dir));
    if (timeout_s <= 0) timeout_s = exp.shard_timeout_s;
    folders.push_back(make_side_folder(side, exp.text));
  }
  const auto t0 = Clock::now();
  try {
    for (int round = 0; round < options.repeats; ++round) {
      result.order.push_back(round_order(sides.size(), round));
      for (std::size_t s : result.order.back()) {
        SideTiming& out = result.sides[s];
        if (!out.error.empty()) continue;
        const auto started = Clock::now();
        out.error = draw_once(program, folders[s], sides[s], ranges, timeout_s, out);
        const double took = seconds_since(started);
        out.seconds += took;
        if (progress) progress(round, s, took);
      }
    }
  } catch (...) {
    std::error_code ec;
    for (const std::string& f : folders) fs::remove_all(f, ec);
    throw;
  }
  result.seconds = seconds_since(t0);
  std::error_code ec;
  for (const std::string& f : folders) fs::remove_all(f, ec);
  return result;
}

}  // namespace ra::audit
