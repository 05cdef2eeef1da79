// A worker that serves many shards of one platform, one after another (`worker-serve DIR
// PLATFORM`, started by `run`): the process, the GL context, the shaders and the effective-grid
// measurement are paid for once, not once per shard (45 ms per llvmpipe shard, 65 ms per softpipe
// one: 26 s of the full nist2008 run). Crash isolation stays per shard: the coordinator sends one
// shard at a time, so a crash or hang names the shard being run, which is then re-run and
// bisected in processes of its own (runner/shard_recovery.h), as a one-shard worker's would be.
//
// Protocol: one line each way per shard (rundir/shard_command.h). An error ends the server as it
// ends a one-shard worker: its last words on the message pipe, exit status 1 or 2.
// Each shard's output (stdout and stderr) goes to its own log, as a one-shard worker's does.
#pragma once

#include <istream>
#include <string>

#include "rundir/shard.h"
#include "rundir/shard_command.h"

namespace ra::runner {

// The server's loop: reads commands from `commands` until its end, runs each shard in one
// ShardSession of `platform`, replies on the message pipe. Throws what a shard throws. `alone`:
// every primitive drawn alone (ShardSession::draw_alone), for timing comparisons.
void serve_shards(const std::string& run_dir, const rundir::Experiment& exp, const std::string& platform,
                  std::istream& commands, bool alone = false);

}  // namespace ra::runner
