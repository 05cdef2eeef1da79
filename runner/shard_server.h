// A worker that serves many shards of one platform, one after another (`worker-serve DIR
// PLATFORM`, started by `run`): the process, the GL context, the shaders and the effective-grid
// measurement are paid for once, not once per shard (45 ms per llvmpipe shard, 65 ms per softpipe
// one: 26 s of the full nist2008 run). Crash isolation stays per shard: the coordinator sends one
// shard at a time, so a crash or hang names the shard being run, which is then re-run and
// bisected in processes of its own (runner/shard_recovery.h), as a one-shard worker's would be.
//
// Protocol, one line each way per shard:
// - coordinator -> server (its stdin): a JSON object {"kind", "view", "begin", "end",
//   "records_dir", "log"}; end of input: the server exits 0.
// - server -> coordinator (its message pipe, ChildSpec::message_pipe): "shard-ok <id>" once the
//   shard's records file is committed. An error ends the server as it ends a one-shard worker:
//   its last words on the same pipe, exit status 1 or 2.
// Each shard's output (stdout and stderr) goes to its own log, as a one-shard worker's does.
#pragma once

#include <istream>
#include <string>

#include "rundir/shard.h"

namespace ra::runner {

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

// The server's loop: reads commands from `commands` until its end, runs each shard in one
// ShardSession of `platform`, replies on the message pipe. Throws what a shard throws.
void serve_shards(const std::string& run_dir, const rundir::Experiment& exp, const std::string& platform,
                  std::istream& commands);

}  // namespace ra::runner
