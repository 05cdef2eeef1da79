#include "runner/shard_server.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "rundir/experiment.h"
#include "runner/shard_session.h"
#include "util/child_process.h"

namespace ra::runner {
namespace {

// stdout and stderr to `path` from now on (truncated), as ChildSpec::log_to does at start.
void redirect_output(const std::string& path) {
  std::fflush(stdout);
  std::fflush(stderr);
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error("cannot open " + path + ": " + std::strerror(errno));
  ::dup2(fd, 1);
  ::dup2(fd, 2);
  ::close(fd);
}

}  // namespace

void serve_shards(const std::string& run_dir, const rundir::Experiment& exp, const std::string& platform,
                  std::istream& commands, bool alone) {
  ShardSession session(run_dir, exp, platform);
  if (alone) session.draw_alone();
  std::string line;
  while (std::getline(commands, line)) {
    if (line.empty()) continue;
    const rundir::ShardCommand c = rundir::parse_shard_command(line, platform);
    redirect_output(c.log);
    session.run(c.shard, c.records_dir);
    std::fflush(stdout);
    std::fflush(stderr);
    util::send_message_to_parent(rundir::shard_done_line(c.shard) + "\n");
  }
}

}  // namespace ra::runner
