// A round's builds as a Slurm job array (see the header).
#include "builds/slurm_builds.h"

#include <cctype>
#include <chrono>
#include <filesystem>
#include <map>
#include <thread>

#include "util/atomic_file.h"
#include "util/child_process.h"
#include "util/errors.h"
#include "util/interrupt.h"
#include "util/shell_quote.h"

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace ra::builds {
namespace {

// What a task's log says of its failure: the build's own message (from its last
// "renderaudit: builds build: " line on), else how it ended.
std::string task_error(const std::string& log, const std::string& how) {
  std::string text;
  try {
    text = util::read_file(log);
  } catch (const std::exception&) {
  }
  const std::size_t at = text.rfind("renderaudit: builds build: ");
  if (at == std::string::npos) return how + " (log: " + log + ")";
  std::string message = text.substr(at + std::string("renderaudit: ").size());
  while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
  return message;
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

class SlurmBuilds : public CommitBuilds {
 public:
  SlurmBuilds(const SourceBuildOptions& o, unsigned jobs, const util::SlurmOptions& slurm,
              std::string dir, std::function<void(const std::string&)> say, double poll_s)
      : o_(o), jobs_(jobs), slurm_(slurm), dir_(std::move(dir)), say_(std::move(say)),
        poll_s_(poll_s) {
    util::validate_slurm_options(slurm_);
    util::require_sbatch_value("the source's git folder", dir_);  // in --output=
    if (!slurm_.allow_node_local)
      for (const auto& [what, path] : {std::pair<std::string, std::string>{"the source's git folder", dir_},
                                       {"the build cache", argv_cache()}})
        if (const std::string why = util::node_local_reason(path); !why.empty())
          throw util::UserError("bisect --slurm: " + what + " " + path + " " + why +
                                "; every node builds there. Put the source and the build cache "
                                "on a shared file system (or --allow-node-local on a one-node "
                                "cluster)");
  }
  ~SlurmBuilds() override { cancel_all(); }

  void start(const std::vector<std::string>& slots, std::size_t round) override {
    cancel_all();
    round_ = round;
    tasks_.assign(slots.size(), Task{});
    t0_ = Clock::now();
    said_.clear();
    std::error_code ec;
    fs::create_directories(dir_ + "/slurm", ec);
    const std::string base = dir_ + "/slurm/round-" + std::to_string(round_);
    const std::string program = fs::read_symlink("/proc/self/exe").string();
    std::vector<std::string> argv = builds_build_argv(program, o_, "", jobs_);
    std::string command;
    for (std::size_t i = 0; i < argv.size(); ++i)
      command += (i ? " " : "") + (i == 3 ? std::string("\"${slots[$k]}\"") : util::shell_quote(argv[i]));
    std::string list = "slots=(''";
    for (const std::string& s : slots) list += " " + util::shell_quote(s);
    list += ")\n";
    std::string script = util::sbatch_header("renderaudit-bisect", int(jobs_), slurm_,
                                       base + "-task-%a.log", false);
    script += "#SBATCH --array=1-" + std::to_string(slots.size()) +
              (slurm_.max_parallel > 0 ? "%" + std::to_string(slurm_.max_parallel) : "") + "\n";
    script +=
        "# One build of a bisection round (written by `renderaudit bisect --slurm`): the slot's\n"
        "# commit into the build cache; its exit status beside its log, for the coordinator.\n"
        "set -u\n" + list +
        "k=$SLURM_ARRAY_TASK_ID\n"
        "echo \"renderaudit: build $k of round " + std::to_string(round_) +
        " on $(hostname) (job ${SLURM_JOB_ID})\"\n" + command + "\n"
        "rc=$?\n"
        "echo $rc > " + util::shell_quote(base) + "-task-$k.exit.tmp && mv " +
        util::shell_quote(base) + "-task-$k.exit.tmp " + util::shell_quote(base) + "-task-$k.exit\n"
        "exit $rc\n";
    script_ = base + ".sbatch";
    base_ = base;
    for (std::size_t i = 0; i < slots.size(); ++i) {
      fs::remove(exit_file(i), ec);
      fs::remove(log_file(i), ec);
    }
    util::write_file_atomic(script_, script);
    const std::string job = util::submit_sbatch(slurm_, {}, script_);
    for (std::size_t i = 0; i < tasks_.size(); ++i) tasks_[i].job = job;
    say_("round " + std::to_string(round_) + ": " + std::to_string(slots.size()) +
         " builds submitted as Slurm array job " + job);
  }

  std::optional<CommitBuildEnd> wait_next() override {
    for (;;) {
      const std::map<std::string, std::string> states = queue_states();
      bool open = false;
      for (std::size_t i = 0; i < tasks_.size(); ++i) {
        Task& t = tasks_[i];
        if (t.ended) continue;
        open = true;
        std::error_code ec;
        std::string how;
        if (fs::exists(exit_file(i), ec)) {
          std::string rc;
          try {
            rc = util::read_file(exit_file(i));
          } catch (const std::exception&) {
          }
          if (rc.rfind("0\n", 0) == 0 || rc == "0") return end(i, true, "");
          how = "the task exited with status " + rc.substr(0, rc.find('\n'));
        } else if (!states.count(id(i))) {
          // Gone from the queue without an exit status: give the file system a few polls.
          if (++t.missing < 5) continue;
          how = "the task left the queue without an exit status (its node died, it was cancelled "
                "or it ran out of time)";
        } else {
          t.missing = 0;
          continue;
        }
        if (t.attempts < 2) {
          say_("round " + std::to_string(round_) + ": build " + std::to_string(i + 1) + " failed (" +
               how + "); submitting it again");
          fs::remove(exit_file(i), ec);
          t.job = util::submit_sbatch(slurm_, {"--array=" + std::to_string(i + 1)}, script_);
          t.attempts = 2;
          t.missing = 0;
          continue;
        }
        return end(i, false, task_error(log_file(i), how));
      }
      if (!open) return std::nullopt;
      say_state(states);
      if (util::interrupt_signal() != 0) {
        cancel_all();
        util::throw_if_interrupted();
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(int(poll_s_ * 1000)));
    }
  }

  void cancel(std::size_t index) override {
    Task& t = tasks_.at(index);
    if (t.ended) return;
    t.ended = true;
    scancel(id(index));
  }

  void cancel_all() override {
    for (std::size_t i = 0; i < tasks_.size(); ++i) cancel(i);
  }

 private:
  struct Task {
    std::string job;
    int attempts = 1, missing = 0;
    bool ended = false;
  };
  std::string id(std::size_t i) const { return tasks_[i].job + "_" + std::to_string(i + 1); }
  std::string exit_file(std::size_t i) const { return base_ + "-task-" + std::to_string(i + 1) + ".exit"; }
  std::string log_file(std::size_t i) const { return base_ + "-task-" + std::to_string(i + 1) + ".log"; }
  std::string argv_cache() const { return builds_build_argv("", o_, "", 1)[5]; }

  std::optional<CommitBuildEnd> end(std::size_t i, bool ok, const std::string& error) {
    tasks_[i].ended = true;
    CommitBuildEnd e;
    e.index = i;
    e.ok = ok;
    e.error = error;
    e.attempts = tasks_[i].attempts;
    e.seconds = std::chrono::duration<double>(Clock::now() - t0_).count();
    return e;
  }

  // "JOB_TASK" -> state (PENDING, RUNNING, ...) of the round's tasks still in the queue.
  std::map<std::string, std::string> queue_states() const {
    std::string jobs;
    for (const Task& t : tasks_)
      if (!t.ended && jobs.find(t.job) == std::string::npos) jobs += (jobs.empty() ? "" : ",") + t.job;
    std::map<std::string, std::string> out;
    if (jobs.empty()) return out;
    util::ChildSpec spec;
    spec.argv = {"squeue", "-h", "-r", "-j", jobs, "-o", "%i %T"};
    spec.capture_output = true;
    spec.stdin_null = true;
    const util::ProgramResult r = util::run_program(spec);
    for (std::size_t at = 0; at < r.output.size();) {
      const std::size_t nl = std::min(r.output.find('\n', at), r.output.size());
      const std::string line = r.output.substr(at, nl - at);
      if (const std::size_t sp = line.find(' '); sp != std::string::npos)
        out[line.substr(0, sp)] = line.substr(sp + 1);
      at = nl + 1;
    }
    // squeue failing (the controller busy) must not read as every task gone; a job the controller
    // has forgotten (long ended) is gone.
    if (!r.exited_ok() && r.output.find("Invalid job id") == std::string::npos)
      for (std::size_t i = 0; i < tasks_.size(); ++i) out[id(i)] = "UNKNOWN";
    return out;
  }

  void say_state(const std::map<std::string, std::string>& states) {
    std::map<std::string, int> count;
    for (std::size_t i = 0; i < tasks_.size(); ++i)
      count[tasks_[i].ended ? "ended" : states.count(id(i)) ? states.at(id(i)) : "ending"]++;
    std::string text;
    for (const auto& [state, n] : count)
      text += (text.empty() ? "" : ", ") + std::to_string(n) + " " + lower(state);
    if (text == said_) return;
    said_ = text;
    say_("round " + std::to_string(round_) + " on Slurm: " + text);
  }

  void scancel(const std::string& task) const {
    util::ChildSpec spec;
    spec.argv = {"scancel", task};
    spec.capture_output = true;
    spec.stdin_null = true;
    util::run_program(spec);
  }

  SourceBuildOptions o_;
  unsigned jobs_;
  util::SlurmOptions slurm_;
  std::string dir_, script_, base_, said_;
  std::function<void(const std::string&)> say_;
  double poll_s_;
  std::size_t round_ = 0;
  std::vector<Task> tasks_;
  Clock::time_point t0_;
};

}  // namespace

std::unique_ptr<CommitBuilds> slurm_commit_builds(const SourceBuildOptions& o, unsigned jobs,
                                                  const util::SlurmOptions& slurm, const std::string& dir,
                                                  std::function<void(const std::string&)> say,
                                                  double poll_s) {
  return std::make_unique<SlurmBuilds>(o, jobs, slurm, dir, std::move(say), poll_s);
}

}  // namespace ra::builds
