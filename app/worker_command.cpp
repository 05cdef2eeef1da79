// `renderaudit worker DIR PLATFORM KIND VIEW BEGIN END [--records-dir D]`: runs one shard (or a
// part of one, when bisecting a crash) in this process. `renderaudit serve-shards DIR PLATFORM`:
// runs the shards of one platform that arrive on stdin (runner/shard_server.h). Both are started
// by `renderaudit run`; not meant to be typed by hand.
#include <iostream>

#include "app/commands.h"
#include "runner/shard_session.h"
#include "util/errors.h"
#include "rundir/experiment.h"
#include "rundir/shard.h"
#include "runner/shard_server.h"

namespace ra::app {

void register_worker_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("worker", "internal: run one shard (started by `run`)");
  cmd->group("");  // hidden from --help
  static std::string dir, platform, kind, records_dir;
  static int view = 0;
  static uint64_t begin = 0, end = 0;
  cmd->add_option("dir", dir)->required();
  cmd->add_option("platform", platform)->required();
  cmd->add_option("kind", kind)->required();
  cmd->add_option("view", view)->required();
  cmd->add_option("begin", begin)->required();
  cmd->add_option("end", end)->required();
  cmd->add_option("--records-dir", records_dir, "where the records file goes (default DIR/records)");
  cmd->callback([&exit_code] {
    const rundir::Experiment exp = rundir::load_experiment(dir + "/experiment.toml");
    rundir::Shard shard{platform, geometry::Kind::kPoint, view, begin, end};
    if (!geometry::parse_kind(kind, &shard.kind))
      throw util::UserError("unknown kind '" + kind + "'");
    runner::run_shard(dir, exp, shard, records_dir);
    exit_code = kExitOk;
  });

  auto* serve = app.add_subcommand("serve-shards", "internal: run the shards sent on stdin");
  serve->group("");
  static std::string serve_dir, serve_platform;
  serve->add_option("dir", serve_dir)->required();
  serve->add_option("platform", serve_platform)->required();
  serve->callback([&exit_code] {
    const rundir::Experiment exp = rundir::load_experiment(serve_dir + "/experiment.toml");
    runner::serve_shards(serve_dir, exp, serve_platform, std::cin);
    exit_code = kExitOk;
  });
}

}  // namespace ra::app
