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

constexpr const char* kDone = "shard-ok ";

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

std::string shard_command_line(const ShardCommand& c) {
  const nlohmann::json j = {{"kind", geometry::kind_name(c.shard.kind)},
                            {"view", c.shard.view},
                            {"begin", c.shard.begin},
                            {"end", c.shard.end},
                            {"records_dir", c.records_dir},
                            {"log", c.log}};
  return j.dump();  // one line: dump() escapes newlines inside strings
}

ShardCommand parse_shard_command(const std::string& line, const std::string& platform) {
  ShardCommand c;
  try {
    const nlohmann::json j = nlohmann::json::parse(line);
    c.shard.platform = platform;
    if (!geometry::parse_kind(j.at("kind").get<std::string>(), &c.shard.kind))
      throw std::runtime_error("unknown kind");
    c.shard.view = j.at("view").get<int>();
    c.shard.begin = j.at("begin").get<uint64_t>();
    c.shard.end = j.at("end").get<uint64_t>();
    c.records_dir = j.at("records_dir").get<std::string>();
    c.log = j.at("log").get<std::string>();
  } catch (const std::exception& e) {
    throw std::runtime_error("not a shard command: '" + line + "' (" + e.what() + ")");
  }
  if (c.shard.end < c.shard.begin)
    throw std::runtime_error("not a shard command: '" + line + "' (end before begin)");
  return c;
}

std::string shard_done_line(const rundir::Shard& shard) { return kDone + shard.id(); }

bool parse_shard_done(const std::string& line, std::string* id) {
  if (line.compare(0, std::strlen(kDone), kDone) != 0) return false;
  *id = line.substr(std::strlen(kDone));
  return true;
}

void serve_shards(const std::string& run_dir, const rundir::Experiment& exp, const std::string& platform,
                  std::istream& commands) {
  ShardSession session(run_dir, exp, platform);
  std::string line;
  while (std::getline(commands, line)) {
    if (line.empty()) continue;
    const ShardCommand c = parse_shard_command(line, platform);
    redirect_output(c.log);
    session.run(c.shard, c.records_dir);
    std::fflush(stdout);
    std::fflush(stderr);
    util::send_message_to_parent(shard_done_line(c.shard) + "\n");
  }
}

}  // namespace ra::runner
