// Which shards a run holds and in which order they start (see the header).
#include "runner/run_plan.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "rundir/shard_cost.h"
#include "rundir/shard_file.h"
#include "rundir/shard_records.h"
#include "util/atomic_file.h"
#include "util/errors.h"

namespace fs = std::filesystem;

namespace ra::runner {

void require_experiment_platforms(const rundir::Experiment& exp, const std::string& experiment_path,
                                  const std::vector<std::string>& only_platforms) {
  for (const auto& p : only_platforms)
    if (std::find(exp.platforms.begin(), exp.platforms.end(), p) == exp.platforms.end())
      throw util::UserError(experiment_path + ": --platform " + p +
                            " is not one of the experiment's platforms");
}

std::vector<rundir::Shard> shards_of_run(const rundir::Experiment& exp,
                                 const std::vector<std::string>& only_platforms,
                                 const std::optional<rundir::Slice>& slice) {
  std::vector<rundir::Shard> all = rundir::plan_shards(exp);
  if (!only_platforms.empty()) {
    all.erase(std::remove_if(all.begin(), all.end(), [&](const rundir::Shard& s) {
                return std::find(only_platforms.begin(), only_platforms.end(), s.platform) ==
                       only_platforms.end();
              }),
              all.end());
  }
  if (slice && size_t(slice->count) > all.size())
    throw util::UserError("--slice " + std::to_string(slice->index) + "/" +
                          std::to_string(slice->count) + ": the run has only " +
                          std::to_string(all.size()) + " shards (allowed: N from 1 to " +
                          std::to_string(all.size()) + ")");
  if (slice) all = rundir::shards_of_slice(all, exp, *slice);
  return all;
}

RunQueue queue_shards(const std::vector<rundir::Shard>& shards, const rundir::Experiment& exp,
                      const std::string& dir, bool largest_cost_first, double timeout_s) {
  RunQueue q;
  std::vector<rundir::Shard> queued;
  for (const rundir::Shard& s : shards) {
    const rundir::ShardRecordsFile file = rundir::find_shard_records(dir, s);  // the seal rule, as readers apply it
    if (!file.path.empty()) {
      const std::string& path = file.path;
      const std::string& damage = file.damage;
      if (damage.empty()) {
        ++q.done_before;  // finished by an earlier invocation: kept as is
        continue;
      }
      // Never counted: set aside (not deleted: it is evidence) and redone.
      const std::string kept = util::keep_damaged_copy(path, true);
      std::fprintf(stderr,
                   "renderaudit: %s: not a complete shard file: %s; kept as %s, redoing shard %s\n",
                   path.c_str(), damage.c_str(), kept.c_str(), s.id().c_str());
      q.damaged.push_back({s.id(), damage});
    }
    queued.push_back(s);
  }
  if (largest_cost_first) queued = rundir::largest_expected_cost_first(std::move(queued), exp);
  for (rundir::Shard& s : queued) q.todo.push_back(WorkItem{std::move(s), "", 1, timeout_s});
  return q;
}

double expected_cost_of(const rundir::Shard& s, const rundir::Experiment& exp) {
  for (const geometry::View& v : exp.views)
    if (v.id == s.view) return rundir::expected_shard_cost_us(s, v);
  return double(s.size());
}

}  // namespace ra::runner
