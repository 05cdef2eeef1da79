#include "rundir/shard_command.h"

#include <cstring>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace ra::rundir {
namespace {

constexpr const char* kDone = "shard-ok ";

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

}  // namespace ra::rundir
