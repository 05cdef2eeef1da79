// The command that repeats a bisection, as the report shows it (see triage/bisect.h).
#include <cstdio>

#include "triage/bisect.h"
#include "util/program_name.h"
#include "util/shell_quote.h"

namespace ra::triage {

std::string bisect_command_line(const BisectOptions& o) {
  using util::shell_quote;
  std::string line = util::program_for_commands() + " bisect " + shell_quote(o.run_dir);
  if (!o.good_platform.empty())
    line += " --between " + shell_quote(o.good_platform) + " " + shell_quote(o.bad_platform);
  if (!o.baseline_run.empty()) line += " --baseline " + shell_quote(o.baseline_run);
  line += " --source " + shell_quote(o.source) + " --good " + shell_quote(o.good_ref) + " --bad " +
          shell_quote(o.bad_ref);
  if (!o.platform.empty()) line += " --platform " + shell_quote(o.platform);
  for (const std::string& k : o.kinds) line += " --kind " + shell_quote(k);
  for (int v : o.views) line += " --view " + std::to_string(v);
  for (const std::string& p : o.primitives) line += " --primitive " + shell_quote(p);
  if (o.max_primitives != BisectOptions{}.max_primitives)
    line += " --max-primitives " + std::to_string(o.max_primitives);
  if (!o.out_dir.empty()) line += " --out " + shell_quote(o.out_dir);
  if (!o.build.cache.empty()) line += " --cache " + shell_quote(o.build.cache);
  if (o.build.llvm_config != builds::SourceBuildOptions{}.llvm_config)
    line += " --llvm-config " + shell_quote(o.build.llvm_config);
  for (const std::string& m : o.build.meson_options) line += " " + shell_quote(m);
  if (!o.build.build_command.empty()) line += " --build-command " + shell_quote(o.build.build_command);
  if (!o.build.incremental) line += " --fresh-builds";
  if (o.jobs) line += " --jobs " + std::to_string(o.jobs);
  if (!o.pictures) line += " --no-pictures";
  if (o.ways != 1) line += " --ways " + std::to_string(o.ways);
  if (o.slurm) {
    const util::SlurmOptions& s = o.slurm_options;
    line += " --slurm";
    if (!s.partition.empty()) line += " --partition " + shell_quote(s.partition);
    if (s.max_parallel) line += " --max-parallel " + std::to_string(s.max_parallel);
    if (!s.time_limit.empty()) line += " --time-limit " + shell_quote(s.time_limit);
    if (s.allow_node_local) line += " --allow-node-local";
  }
  if (o.speed.enabled) {
    const BisectSpeedOptions d;
    line += " --speed";
    if (o.speed.repeats != d.repeats) line += " --speed-repeats " + std::to_string(o.speed.repeats);
    if (o.speed.per_view != d.per_view)
      line += " --speed-primitives " + std::to_string(o.speed.per_view);
    if (o.speed.threshold != d.threshold) {
      char t[32];
      std::snprintf(t, sizeof t, "%g", o.speed.threshold);
      line += std::string(" --speed-threshold ") + t;
    }
  }
  if (!o.paths.empty()) {
    line += " --";
    for (const std::string& p : o.paths) line += " " + shell_quote(p);
  }
  return line;
}

}  // namespace ra::triage
