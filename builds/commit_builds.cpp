// Builds at once as child processes (see the header).
#include "builds/commit_builds.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <filesystem>
#include <thread>

#include "rundir/build_record.h"
#include "util/child_process.h"
#include "util/interrupt.h"

using Clock = std::chrono::steady_clock;

namespace ra::builds {

std::vector<std::string> builds_build_argv(const std::string& program, const SourceBuildOptions& o,
                                           const std::string& slot, unsigned jobs) {
  std::vector<std::string> argv = {program, "builds", "build", slot, "--cache",
                                   o.cache.empty() ? rundir::build_cache_dir() : o.cache,
                                   "--llvm-config", o.llvm_config, "--jobs", std::to_string(jobs),
                                   "--no-probe"};
  if (o.incremental) argv.push_back("--incremental");
  if (!o.build_command.empty()) argv.insert(argv.end(), {"--build-command", o.build_command});
  for (const std::string& m : o.meson_options) argv.push_back("--meson-option=" + m);
  return argv;
}

unsigned jobs_per_build(unsigned cores, std::size_t k) {
  return std::max(1u, k ? unsigned(cores / k) : cores);
}

namespace {

class LocalBuilds : public CommitBuilds {
 public:
  LocalBuilds(const SourceBuildOptions& o, unsigned jobs, std::string log_dir)
      : o_(o), jobs_(jobs), log_dir_(std::move(log_dir)) {}
  ~LocalBuilds() override { cancel_all(); }

  void start(const std::vector<std::string>& slots, std::size_t) override {
    cancel_all();
    builds_.clear();
    t0_ = Clock::now();
    const std::string program = std::filesystem::read_symlink("/proc/self/exe").string();
    for (std::size_t i = 0; i < slots.size(); ++i) {
      util::ChildSpec spec;
      spec.argv = builds_build_argv(program, o_, slots[i], jobs_);
      spec.stdin_null = true;
      spec.log_to(log_dir_ + "/build-" + std::to_string(i + 1) + ".log");
      spec.own_process_group = true;  // a cancel stops the build's compilers too
      spec.message_pipe = true;       // the build's refusal, word for word
      spec.death_signal = SIGTERM;    // it stops its own build's group when this process dies
      builds_.push_back({util::start_child(spec), false});
    }
  }

  std::optional<CommitBuildEnd> wait_next() override {
    for (;;) {
      bool running = false;
      for (std::size_t i = 0; i < builds_.size(); ++i) {
        Build& b = builds_[i];
        if (b.ended) continue;
        int status = 0;
        const pid_t done = ::waitpid(b.child.pid, &status, WNOHANG);
        if (done == 0 || (done < 0 && errno == EINTR)) {
          running = true;
          continue;
        }
        b.ended = true;
        CommitBuildEnd e;
        e.index = i;
        e.seconds = std::chrono::duration<double>(Clock::now() - t0_).count();
        e.ok = done == b.child.pid && WIFEXITED(status) && WEXITSTATUS(status) == 0;
        const std::string message = finish(b);
        if (!e.ok)
          e.error = !message.empty() ? message
                                     : "renderaudit builds build " +
                                           util::describe_exit_status(status) + " (log: " +
                                           log_dir_ + "/build-" + std::to_string(i + 1) + ".log)";
        return e;
      }
      if (!running) return std::nullopt;
      if (util::interrupt_signal() != 0) {
        cancel_all();
        util::throw_if_interrupted();
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }

  void cancel(std::size_t index) override {
    Build& b = builds_.at(index);
    if (b.ended) return;
    b.ended = true;
    stop(b.child.pid);
    finish(b);
  }

  void cancel_all() override {
    for (std::size_t i = 0; i < builds_.size(); ++i) cancel(i);
  }

 private:
  struct Build {
    util::Child child;
    bool ended = false;
  };
  // The message the build sent before it ended; its descriptors closed.
  static std::string finish(Build& b) {
    std::string message;
    if (b.child.message_fd >= 0) {
      message = util::drain_fd(b.child.message_fd);
      ::close(b.child.message_fd);
      b.child.message_fd = -1;
    }
    return message;
  }
  // SIGTERM to the build's group (it stops its own compilers' group), SIGKILL after 10 s.
  static void stop(pid_t pid) {
    ::kill(-pid, SIGTERM);
    const auto until = Clock::now() + std::chrono::seconds(10);
    int status = 0;
    while (::waitpid(pid, &status, WNOHANG) == 0) {
      if (Clock::now() > until) {
        ::kill(-pid, SIGKILL);
        util::wait_child(pid);
        return;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }

  SourceBuildOptions o_;
  unsigned jobs_;
  std::string log_dir_;
  std::vector<Build> builds_;
  Clock::time_point t0_;
};

}  // namespace

std::unique_ptr<CommitBuilds> local_commit_builds(const SourceBuildOptions& o, unsigned jobs,
                                                  const std::string& log_dir) {
  return std::make_unique<LocalBuilds>(o, jobs, log_dir);
}

}  // namespace ra::builds
