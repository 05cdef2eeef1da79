// The line protocol between `run` (or any coordinator) and a shard server (`serve-shards DIR
// PLATFORM`, runner/shard_server.h), one line each way per shard:
// - coordinator -> server (its stdin): a JSON object {"kind", "view", "begin", "end",
//   "records_dir", "log"}; end of input: the server exits 0.
// - server -> coordinator (its message pipe, util/child_process.h ChildSpec::message_pipe):
//   "shard-ok <id>" once the shard's records file is committed.
// Here, below runner/, so that a coordinator that links no driver (the audit's timing) speaks it.
#pragma once

#include <string>

#include "rundir/shard.h"

namespace ra::rundir {

struct ShardCommand {
  rundir::Shard shard;
  std::string records_dir;  // where the records file goes
  std::string log;          // the shard's log: the server's stdout and stderr while it runs
};

// One command line (no newline) for `command`, and back; parse throws std::runtime_error on a
// line that is not one.
std::string shard_command_line(const ShardCommand& command);
ShardCommand parse_shard_command(const std::string& line, const std::string& platform);

// The reply that says `shard` is done (no newline), and whether `line` is one (then *id is set).
std::string shard_done_line(const rundir::Shard& shard);
bool parse_shard_done(const std::string& line, std::string* id);

}  // namespace ra::rundir
