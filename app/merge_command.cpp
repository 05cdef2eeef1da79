// `renderaudit merge DIR_1 ... DIR_N --out DIR`: slices of one run gathered into one run directory
// (runner/run_merge.h), then its summary.
#include <cstdio>

#include "analysis/run_summary.h"
#include "app/commands.h"
#include "runner/run_merge.h"

namespace ra::app {

void register_merge_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "merge",
      "Gather run directories of one experiment (the slices of `run --slice K/N`, run on\n"
      "several machines) into one run directory: every planned shard taken once from the first\n"
      "input that holds it whole, one manifest recording every input's slice, host, times and\n"
      "driver strings. Exit 0 when every shard is there, 1 when some are missing (listed) or the\n"
      "records hold primitives that crashed or hung.");
  struct Options {
    runner::MergeOptions opt;
  };
  const auto opts = std::make_shared<Options>();  // alive as long as the callbacks
  cmd->add_option("inputs", opts->opt.inputs, "run directories (slices)")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--out,-o", opts->opt.out_dir, "the merged run directory")->required();
  cmd->add_flag("--allow-driver-mismatch", opts->opt.allow_driver_mismatch,
                "merge inputs whose platforms report other GL_RENDERER / GL_VERSION strings, or "
                "drew with other driver library bytes (drivers/P.json build.libraries)");
  cmd->callback([opts, &exit_code] {
    const runner::MergeResult r = runner::merge_runs(opts->opt);
    std::printf(
        "%s: %zu of %zu shards (%zu copied now, %zu found in several inputs and taken "
        "once)\n",
        opts->opt.out_dir.c_str(), r.shards_present, r.shards_total, r.shards_copied,
        r.shards_in_several_inputs);
    for (const std::string& d : r.damaged)  // the seal rule: never taken, always named
      std::printf("  damaged, not taken: %s\n", d.c_str());
    for (std::size_t i = 0; i < r.missing.size() && i < 20; ++i)
      std::printf("  missing: %s\n", r.missing[i].c_str());
    if (r.missing.size() > 20) std::printf("  ... and %zu more\n", r.missing.size() - 20);
    analysis::write_run_summary(opts->opt.out_dir);
    std::printf("summary: %s/summary.md\n", opts->opt.out_dir.c_str());
    if (r.failed_primitives > 0)
      std::printf("  %zu primitives recorded as crash or timeout (manifest.json lists them)\n",
                  r.failed_primitives);
    exit_code = r.missing.empty() && r.failed_primitives == 0 ? kExitOk : kExitFindings;
  });
}

}  // namespace ra::app
