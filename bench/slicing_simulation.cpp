// `slicing_simulation RUN_DIR [--cores C] [--nodes 1,4,16,64]`: how a run would scale out. From
// the measured wall time of each shard (RUN_DIR/manifest.json "shard_seconds") it simulates the run
// cut into N slices (rundir/slicing.h, as `run --slice K/N` cuts it) on N nodes of C cores, each
// node starting its shards largest expected cost first on whichever core frees first (as the run
// coordinator does), and prints the makespan against the ideal total / (N x C), beside the same
// for slices dealt by count (every N-th shard, as deqp-runner's --fraction deals tests).
#include <algorithm>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <queue>
#include <sstream>
#include <string>
#include <vector>

#include "rundir/experiment.h"
#include "rundir/manifest.h"
#include "rundir/run_experiment.h"
#include "rundir/run_folder.h"
#include "rundir/shard.h"
#include "rundir/shard_cost.h"
#include "rundir/slicing.h"
#include "util/atomic_file.h"

using namespace ra;

namespace {

// Makespan of `shards` on `cores` cores: started in largest-expected-cost order, each on the
// first core to free; durations are the measured ones.
double node_makespan(const std::vector<ra::rundir::Shard>& shards,
                     const ra::rundir::Experiment& exp, int cores,
                     const std::map<std::string, double>& seconds) {
  std::priority_queue<double, std::vector<double>, std::greater<double>> free_at;
  for (int c = 0; c < cores; ++c) free_at.push(0);
  double end = 0;
  for (const ra::rundir::Shard& s : ra::rundir::largest_expected_cost_first(shards, exp)) {
    const double start = free_at.top();
    free_at.pop();
    const double finish = start + seconds.at(s.id());
    free_at.push(finish);
    end = std::max(end, finish);
  }
  return end;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: slicing_simulation RUN_DIR [--cores C] [--nodes 1,4,16,64]\n");
    return 2;
  }
  const std::string dir = argv[1];
  int cores = 2;
  std::vector<int> node_counts = {1, 4, 16, 64};
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--cores") {
      cores = std::max(1, std::atoi(argv[i + 1]));
    } else if (a == "--nodes") {
      node_counts.clear();
      std::stringstream list(argv[i + 1]);
      for (std::string n; std::getline(list, n, ',');) node_counts.push_back(std::max(1, std::stoi(n)));
    } else {
      std::fprintf(stderr, "slicing_simulation: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  const ra::rundir::Experiment exp = ra::rundir::load_run_experiment(dir);
  const ra::rundir::RunManifest manifest =
      ra::rundir::read_manifest_file(ra::rundir::run_folder::manifest(dir));
  std::map<std::string, double> seconds =
      manifest.shard_seconds.value_or(std::map<std::string, double>{});
  std::vector<ra::rundir::Shard> shards;
  for (const ra::rundir::Shard& s : ra::rundir::plan_shards(exp))
    if (seconds.count(s.id())) shards.push_back(s);
  if (shards.empty()) {
    std::fprintf(stderr, "slicing_simulation: %s/manifest.json has no shard_seconds of this plan\n",
                 dir.c_str());
    return 2;
  }
  double total = 0;
  for (const ra::rundir::Shard& s : shards) total += seconds[s.id()];
  std::printf("%zu shards with measured times, %.0f worker-seconds; nodes of %d cores\n",
              shards.size(), total, cores);
  std::printf("%6s %12s %12s %10s %14s %10s\n", "nodes", "ideal s", "by cost s", "efficiency",
              "by count s", "efficiency");
  for (int n : node_counts) {
    double by_cost = 0, by_count = 0;
    for (int k = 1; k <= n; ++k) {
      by_cost = std::max(by_cost, node_makespan(ra::rundir::shards_of_slice(shards, exp, {k, n}),
                                                exp, cores, seconds));
      std::vector<ra::rundir::Shard> dealt;
      for (std::size_t i = std::size_t(k - 1); i < shards.size(); i += std::size_t(n))
        dealt.push_back(shards[i]);
      by_count = std::max(by_count, node_makespan(dealt, exp, cores, seconds));
    }
    const double ideal = total / (double(n) * cores);
    std::printf("%6d %12.1f %12.1f %9.1f%% %14.1f %9.1f%%\n", n, ideal, by_cost,
                100 * ideal / by_cost, by_count, 100 * ideal / by_count);
  }
  return 0;
}
