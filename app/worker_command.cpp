// `renderaudit worker DIR PLATFORM KIND VIEW BEGIN END [--records-dir D]`: runs one shard (or a
// part of one, when bisecting a crash) in this process. `renderaudit serve-shards DIR PLATFORM`:
// runs the shards of one platform that arrive on stdin (runner/shard_server.h). Both are started
// by `renderaudit run`; not meant to be typed by hand.
#include <iostream>

#include "app/commands.h"
#include "rundir/experiment.h"
#include "rundir/run_experiment.h"
#include "rundir/shard.h"
#include "runner/shard_server.h"
#include "runner/shard_session.h"
#include "util/errors.h"

namespace ra::app {

void register_worker_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("worker", "internal: run one shard (started by `run`)");
  cmd->group("");  // hidden from --help
  struct Options {
    std::string dir;
    std::string platform;
    std::string kind;
    std::string records_dir;
    int view = 0;
    uint64_t begin = 0;
    uint64_t end = 0;
    std::string serve_dir;
    std::string serve_platform;
    bool alone = false;
  };
  const auto opts = std::make_shared<Options>();  // alive as long as the callbacks
  cmd->add_option("dir", opts->dir)->required();
  cmd->add_option("platform", opts->platform)->required();
  cmd->add_option("kind", opts->kind)->required();
  cmd->add_option("view", opts->view)->required();
  cmd->add_option("begin", opts->begin)->required();
  cmd->add_option("end", opts->end)->required();
  cmd->add_option("--records-dir", opts->records_dir,
                  "where the records file goes (default DIR/records)");
  cmd->callback([opts, &exit_code] {
    const rundir::Experiment exp = rundir::load_run_experiment(opts->dir);
    rundir::Shard shard{opts->platform, geometry::Kind::kPoint, opts->view, opts->begin, opts->end};
    if (!geometry::parse_kind(opts->kind, &shard.kind))
      throw util::UserError("unknown kind '" + opts->kind + "'");
    runner::run_shard(opts->dir, exp, shard, opts->records_dir);
    exit_code = kExitOk;
  });

  auto* serve = app.add_subcommand("serve-shards", "internal: run the shards sent on stdin");
  serve->group("");
  serve->add_option("dir", opts->serve_dir)->required();
  serve->add_option("platform", opts->serve_platform)->required();
  serve->add_flag("--alone", opts->alone, "draw every primitive alone (timing comparisons)");
  serve->callback([opts, &exit_code] {
    const rundir::Experiment exp = rundir::load_run_experiment(opts->serve_dir);
    runner::serve_shards(opts->serve_dir, exp, opts->serve_platform, std::cin, opts->alone);
    exit_code = kExitOk;
  });
}

}  // namespace ra::app
