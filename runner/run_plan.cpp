// Which shards a run holds and in which order they start (see the header).
#include "runner/run_plan.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "runner/shard_cost.h"
#include "runner/shard_file.h"
#include "runner/shard_records.h"
#include "util/errors.h"

namespace fs = std::filesystem;

namespace ra::runner {

void require_experiment_platforms(const Experiment& exp, const std::string& experiment_path,
                                  const std::vector<std::string>& only_platforms) {
  for (const auto& p : only_platforms)
    if (std::find(exp.platforms.begin(), exp.platforms.end(), p) == exp.platforms.end())
      throw util::UserError(experiment_path + ": --platform " + p +
                            " is not one of the experiment's platforms");
}

std::vector<Shard> shards_of_run(const Experiment& exp,
                                 const std::vector<std::string>& only_platforms,
                                 const std::optional<Slice>& slice) {
  std::vector<Shard> all = plan_shards(exp);
  if (!only_platforms.empty()) {
    all.erase(std::remove_if(all.begin(), all.end(), [&](const Shard& s) {
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
  if (slice) all = shards_of_slice(all, exp, *slice);
  return all;
}

RunQueue queue_shards(const std::vector<Shard>& shards, const Experiment& exp,
                      const std::string& dir, bool largest_cost_first, double timeout_s) {
  RunQueue q;
  std::vector<Shard> queued;
  for (const Shard& s : shards) {
    const ShardRecordsFile file = find_shard_records(dir, s);  // the seal rule, as readers apply it
    if (!file.path.empty()) {
      const std::string& path = file.path;
      const std::string& damage = file.damage;
      if (damage.empty()) {
        ++q.done_before;  // finished by an earlier invocation: kept as is
        continue;
      }
      // Never counted: set aside (not deleted: it is evidence) and redone.
      std::fprintf(stderr, "renderaudit: %s: not a complete shard file: %s; redoing shard %s\n",
                   path.c_str(), damage.c_str(), s.id().c_str());
      fs::rename(path, path + ".damaged");
      q.damaged.push_back({s.id(), damage});
    }
    queued.push_back(s);
  }
  if (largest_cost_first) queued = largest_expected_cost_first(std::move(queued), exp);
  for (Shard& s : queued) q.todo.push_back(WorkItem{std::move(s), "", 1, timeout_s});
  return q;
}

double expected_cost_of(const Shard& s, const Experiment& exp) {
  for (const geometry::View& v : exp.views)
    if (v.id == s.view) return expected_shard_cost_us(s, v);
  return double(s.size());
}

}  // namespace ra::runner
