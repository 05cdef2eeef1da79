#include "audit/speed_timing.h"

#include <poll.h>
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

// A shard server of one side for one round: alive for the whole round, drawing when told.
struct Server {
  util::Child child;
  std::string log;
  std::string unread;  // what its message pipe said, not yet taken as replies
  std::string error;   // non-empty: it failed, and why
};

void start_server(Server& s, const std::string& program, const std::string& dir,
                  const TimingSide& side) {
  s.log = rundir::run_folder::logs(dir) + "/serve.log";
  util::ChildSpec spec;
  spec.argv = {program, "serve-shards", dir, side.platform, "--alone"};
  spec.log_to(s.log);
  spec.command_pipe = true;
  spec.message_pipe = true;
  spec.own_process_group = true;
  s.child = util::start_child(spec);
}

// Why a server that stopped answering stopped: its exit status and its log's last line.
std::string why_failed(Server& s, const std::string& what) {
  int status = 0;
  if (::waitpid(s.child.pid, &status, WNOHANG) == s.child.pid) {
    s.child.pid = -1;
    const std::string last = last_nonempty_line(s.log);
    return util::describe_exit_status(status) + (last.empty() ? "" : ": " + last);
  }
  return what;
}

// Sends one shard to the server and waits for its reply; false (and s.error) when it fails or
// takes longer than timeout_s.
bool draw_shard(Server& s, const rundir::Shard& shard, const std::string& records,
                double timeout_s) {
  const std::string line = rundir::shard_command_line({shard, records, s.log}) + "\n";
  for (std::size_t done = 0; done < line.size();) {
    const ssize_t n = ::write(s.child.command_fd, line.data() + done, line.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {  // a server that died: EPIPE (SIGPIPE is ignored by the program)
      s.error = why_failed(s, "its command pipe is closed");
      return false;
    }
    done += std::size_t(n);
  }
  const auto started = Clock::now();
  for (;;) {
    s.unread += util::drain_fd(s.child.message_fd);
    for (std::size_t nl; (nl = s.unread.find('\n')) != std::string::npos;) {
      const std::string reply = s.unread.substr(0, nl);
      s.unread.erase(0, nl + 1);
      std::string id;
      if (rundir::parse_shard_done(reply, &id) && id == shard.id()) return true;
    }
    int status = 0;
    if (::waitpid(s.child.pid, &status, WNOHANG) == s.child.pid) {
      s.child.pid = -1;
      const std::string last = last_nonempty_line(s.log);
      s.error = util::describe_exit_status(status) + (last.empty() ? "" : ": " + last);
      return false;
    }
    if (seconds_since(started) > timeout_s) {
      s.error = "timed out after " + std::to_string(int(timeout_s)) + " s on " + shard.id();
      return false;
    }
    pollfd p{s.child.message_fd, POLLIN, 0};
    ::poll(&p, 1, 20);
  }
}

// Ends a server: end of input, then its exit (killed when it does not come).
void stop_server(Server& s) {
  if (s.child.command_fd >= 0) ::close(s.child.command_fd), s.child.command_fd = -1;
  if (s.child.pid > 0) {
    const auto started = Clock::now();
    int status = 0;
    while (::waitpid(s.child.pid, &status, WNOHANG) != s.child.pid) {
      if (seconds_since(started) > 30) {
        ::kill(-s.child.pid, SIGKILL);
        ::waitpid(s.child.pid, &status, 0);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    s.child.pid = -1;
  }
  if (s.child.message_fd >= 0) ::close(s.child.message_fd), s.child.message_fd = -1;
}

}  // namespace

std::vector<RoundTimes> common_round_times(const std::vector<const SideTiming*>& sides,
                                           const std::vector<TimedKey>& keys, int rounds) {
  std::vector<RoundTimes> out(sides.size());
  for (const TimedKey& key : keys) {
    std::vector<const std::vector<double>*> times;
    for (const SideTiming* side : sides) {
      const auto it = side->render_us.find(key);
      if (it == side->render_us.end() || int(it->second.size()) != rounds) break;
      bool positive = true;
      for (double t : it->second) positive = positive && t > 0;
      if (!positive) break;
      times.push_back(&it->second);
    }
    if (times.size() != sides.size()) continue;
    for (std::size_t s = 0; s < sides.size(); ++s) out[s].push_back(*times[s]);
  }
  return out;
}

void append_rounds(SideTiming& into, const SideTiming& more) {
  for (const auto& [key, rounds] : more.render_us) {
    std::vector<double>& to = into.render_us[key];
    to.insert(to.end(), rounds.begin(), rounds.end());
  }
  if (into.error.empty()) into.error = more.error;
  into.seconds += more.seconds;
}

std::vector<std::size_t> round_order(std::size_t sides, int round) {
  std::vector<std::size_t> order(sides);
  for (std::size_t i = 0; i < sides; ++i) order[i] = round % 2 == 0 ? i : sides - 1 - i;
  return order;
}

namespace {

// One round: a fresh server per side, each warmed up on every range, then the ranges drawn in
// turn, one side after another, the sides' order alternating from range to range.
void draw_round(const std::string& program, const std::vector<std::string>& folders,
                const std::vector<TimingSide>& sides, const std::vector<TimingRange>& ranges,
                double timeout_s, int round, TimingResult& result) {
  std::vector<Server> servers(sides.size());
  std::error_code ec;
  for (std::size_t s = 0; s < sides.size(); ++s) {
    if (!result.sides[s].error.empty()) continue;
    for (const std::string& folder : {rundir::run_folder::records(folders[s]),
                                      folders[s] + "/warmup"}) {
      fs::remove_all(folder, ec);
      fs::create_directories(folder);
    }
    start_server(servers[s], program, folders[s], sides[s]);
  }
  auto shard_of = [&](std::size_t s, const TimingRange& r) {
    return rundir::Shard{sides[s].platform, r.kind, r.view, r.begin, r.end};
  };
  // The first pass pays for the driver compiling its code for each new state (llvmpipe's JIT
  // took a third of the first primitives' time); only the second is kept.
  for (std::size_t s = 0; s < sides.size(); ++s)
    for (const TimingRange& r : ranges)
      if (servers[s].child.pid > 0 && servers[s].error.empty())
        draw_shard(servers[s], shard_of(s, r), folders[s] + "/warmup", timeout_s);
  for (std::size_t k = 0; k < ranges.size(); ++k)
    for (std::size_t s : round_order(sides.size(), round + int(k))) {
      Server& server = servers[s];
      if (server.child.pid <= 0 || !server.error.empty()) continue;
      const auto t0 = Clock::now();
      draw_shard(server, shard_of(s, ranges[k]), rundir::run_folder::records(folders[s]),
                 timeout_s);
      result.sides[s].seconds += seconds_since(t0);
    }
  for (std::size_t s = 0; s < sides.size(); ++s) {
    stop_server(servers[s]);
    SideTiming& out = result.sides[s];
    if (!out.error.empty()) continue;
    if (!servers[s].error.empty()) {
      out.error = servers[s].error;
      continue;
    }
    for (const TimingRange& r : ranges) {
      const rundir::Shard shard = shard_of(s, r);
      const rundir::ShardRecordsFile file = rundir::find_shard_records(folders[s], shard);
      if (file.path.empty() || !file.damage.empty()) {
        out.error = file.path.empty() ? "wrote no records for " + shard.id()
                                      : file.path + ": damaged: " + file.damage;
        break;
      }
      rundir::read_records(file.path, [&](const metrics::Record& rec) {
        if (rec.status != metrics::CaseStatus::kOk) return;
        const TimedKey key{int(r.kind), r.view, rec.index};
        out.render_us[key].push_back(rec.render_us);
      });
    }
  }
}

}  // namespace

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
      const auto started = Clock::now();
      draw_round(program, folders, sides, ranges, timeout_s, round, result);
      if (progress) progress(round, sides.size(), seconds_since(started));
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
