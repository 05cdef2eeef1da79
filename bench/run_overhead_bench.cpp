// `run_overhead_bench [--experiment bench/run_overhead.toml] [--rounds 3] [--jobs 2]`: the whole
// run's cost against the drivers' own drawing, the figure the run's overhead is judged by. Each round runs
// the fixed experiment with `renderaudit run` into a fresh directory and reads back its records
// (render_us: the drawing of each primitive, CPU microseconds) and manifest (wall time, each
// shard's worker seconds). Printed: per round, wall x jobs / drawing (1.0 is the floor: the
// drivers drawing on every core without pause), and per platform x kind the worker time per
// primitive beside the drawing per primitive (the per-primitive floor), medians over the rounds.
// `--from RUN_DIR` prints the same tables for a run already made (one round; e.g. the full
// nist2008 run), without running anything. Each round also runs the experiment with
// `--worker-per-shard` (one process per shard), the two alternating, so
// that what serving many shards per process saves is measured side by side.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rundir/manifest.h"
#include "rundir/records_reader.h"
#include "rundir/run_folder.h"
#include "rundir/shard.h"
#include "stats/descriptive.h"
#include "stats/table_writer.h"
#include "util/atomic_file.h"
#include "util/child_process.h"

namespace fs = std::filesystem;
using namespace ra;

namespace {

// The statistics library's median (stats/descriptive.h); 0 for no values.
double median(const std::vector<double>& v) { return v.empty() ? 0 : stats::median(v); }

struct KindCost {
  double drawing_s = 0, worker_s = 0;
  uint64_t primitives = 0;
};

struct Round {
  double wall_s = 0, elapsed_s = 0, busy_s = 0, drawing_s = 0;
  int processes = -1;                      // worker processes started (-1: not recorded)
  std::string workers;                     // "serve-shards" or "per-shard", from the manifest
  std::map<std::string, KindCost> kinds;  // "platform kind"
};

}  // namespace

int main(int argc, char** argv) {
  std::string experiment = "bench/run_overhead.toml", json_out, from;
  int rounds = 3, jobs = 2;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&] { return i + 1 < argc ? std::string(argv[++i]) : std::string(); };
    if (a == "--experiment")
      experiment = next();
    else if (a == "--rounds")
      rounds = std::max(1, std::atoi(next().c_str()));
    else if (a == "--jobs")
      jobs = std::max(1, std::atoi(next().c_str()));
    else if (a == "--json")
      json_out = next();
    else if (a == "--from")
      from = next();
    else {
      std::fprintf(stderr,
                   "usage: run_overhead_bench [--experiment F] [--rounds N] [--jobs J] "
                   "[--json OUT] [--from RUN_DIR]\n");
      return 2;
    }
  }
  const std::string program =
      (fs::read_symlink("/proc/self/exe").parent_path() / "renderaudit").string();
  std::vector<Round> results, per_shard;  // the default (served shards), and --worker-per-shard
  if (!from.empty()) rounds = 1, experiment = ra::rundir::run_folder::experiment(from);
  for (int r = 1; r <= rounds; ++r)
  for (const bool served : {true, false}) {
    if (!from.empty() && !served) continue;
    const std::string dir = !from.empty() ? from
                                          : "outputs/bench/run-overhead/round" + std::to_string(r) +
                                                (served ? "" : "-per-shard");
    Round round;
    if (from.empty()) {
      fs::remove_all(dir);
      ra::util::ChildSpec spec;
      spec.argv = {program, "run",    experiment,           "--out",
                   dir,     "--jobs", std::to_string(jobs), "--quiet"};
      if (!served) spec.argv.push_back("--worker-per-shard");
      spec.capture_output = true;
      spec.stdin_null = true;
      const auto t0 = std::chrono::steady_clock::now();
      const ra::util::ProgramResult res = ra::util::run_program(spec);
      round.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (!res.exited_ok()) {
        std::fprintf(stderr, "run_overhead_bench: %s run failed (%s):\n%s\n", experiment.c_str(),
                     ra::util::describe_exit_status(res.status).c_str(), res.output.c_str());
        return 1;
      }
    }
    const ra::rundir::RunManifest m =
        ra::rundir::read_manifest_file(ra::rundir::run_folder::manifest(dir));
    const ra::rundir::ManifestInvocation* inv = m.last_invocation();
    if (!inv) {
      std::fprintf(stderr, "run_overhead_bench: %s/manifest.json lists no invocation\n", dir.c_str());
      return 1;
    }
    jobs = int(inv->jobs);
    round.elapsed_s = inv->elapsed_s.value_or(0.0);
    round.busy_s = inv->worker_busy_s.value_or(0.0);
    round.processes = inv->worker_processes ? int(*inv->worker_processes) : -1;
    // Manifests without "workers" come from builds that always started a process per shard.
    round.workers = inv->workers.empty() ? "per-shard" : inv->workers;
    for (const auto& [id, seconds] : m.shard_seconds.value_or(std::map<std::string, double>{})) {
      // id: platform.kind.vN.begin-end
      const size_t a = id.find('.'), b = id.find('.', a + 1);
      KindCost& k = round.kinds[id.substr(0, a) + " " + id.substr(a + 1, b - a - 1)];
      k.worker_s += seconds;
    }
    for (const auto& e : fs::directory_iterator(ra::rundir::run_folder::records(dir))) {
      ra::rundir::for_each_record_row(e.path().string(), [&](const ra::rundir::RecordRow& row) {
        const double us = row.number(ra::metrics::RecordColumn::kRenderUs).value_or(0);
        KindCost& k = round.kinds[std::string(row.cell(ra::metrics::RecordColumn::kPlatform)) +
                                  " " + std::string(row.cell(ra::metrics::RecordColumn::kKind))];
        k.drawing_s += us * 1e-6;
        ++k.primitives;
        round.drawing_s += us * 1e-6;
      });
    }
    (served ? results : per_shard).push_back(std::move(round));
  }

  std::printf("\nWhole run against the drivers' own drawing: %s, --jobs %d, %d rounds\n\n",
              experiment.c_str(), jobs, rounds);
  using stats::Align;
  std::printf(
      "%s", stats::markdown_header(
                {"round", "workers", "processes", "wall s", "worker-s", "drawing s (sum render_us)",
                 "wall x jobs / drawing", "worker-s / drawing"},
                {Align::kRight, Align::kDefault, Align::kRight, Align::kRight, Align::kRight,
                 Align::kRight, Align::kRight, Align::kRight})
                .c_str());
  std::vector<double> ratio, worker_ratio, ratio_per_shard, worker_ratio_per_shard;
  auto print_round = [&](size_t r, const Round& x, const char* workers, std::vector<double>& rs,
                         std::vector<double>& ws) {
    rs.push_back(x.elapsed_s * jobs / x.drawing_s);
    ws.push_back(x.busy_s / x.drawing_s);
    const std::string processes = x.processes < 0 ? "?" : std::to_string(x.processes);
    std::printf("| %zu | %s | %s | %.2f | %.2f | %.2f | %.3f | %.3f |\n", r + 1,
                x.workers.empty() ? workers : x.workers.c_str(), processes.c_str(), x.elapsed_s,
                x.busy_s, x.drawing_s, rs.back(), ws.back());
  };
  for (size_t r = 0; r < results.size(); ++r) {
    print_round(r, results[r], "serve-shards", ratio, worker_ratio);
    if (r < per_shard.size())
      print_round(r, per_shard[r], "per-shard", ratio_per_shard, worker_ratio_per_shard);
  }
  std::printf("| median | %s | | | | | **%.3f** | %.3f |\n", results.front().workers.c_str(),
              median(ratio), median(worker_ratio));
  if (!per_shard.empty())
    std::printf("| median | per-shard | | | | | %.3f | %.3f |\n", median(ratio_per_shard),
                median(worker_ratio_per_shard));
  std::printf(
      "\nPer primitive (medians over the rounds, serve-shards): the worker's time (its shard's "
      "wall time / primitives) against the drawing (render_us), the floor\n\n");
  std::printf("%s", stats::markdown_header({"platform", "kind", "primitives", "drawing us",
                                            "worker us", "worker / drawing"},
                                           2)
                        .c_str());
  nlohmann::json out = {{"experiment", experiment},
                        {"jobs", jobs},
                        {"rounds", rounds},
                        {"ratio_median", median(ratio)},
                        {"ratio_median_per_shard", median(ratio_per_shard)},
                        {"kinds", nlohmann::json::array()}};
  for (const auto& [key, first] : results.front().kinds) {
    std::vector<double> draw_us, worker_us;
    for (const Round& x : results) {
      const KindCost& k = x.kinds.at(key);
      draw_us.push_back(1e6 * k.drawing_s / k.primitives);
      worker_us.push_back(1e6 * k.worker_s / k.primitives);
    }
    const double d = median(draw_us), w = median(worker_us);
    const std::string platform = key.substr(0, key.find(' ')), kind = key.substr(key.find(' ') + 1);
    std::printf("| %s | %s | %llu | %.1f | %.1f | %.2f |\n", platform.c_str(), kind.c_str(),
                static_cast<unsigned long long>(first.primitives), d, w, w / d);
    out["kinds"].push_back(
        {{"platform", platform}, {"kind", kind}, {"drawing_us", d}, {"worker_us", w}});
  }
  if (!json_out.empty()) {
    fs::create_directories(fs::path(json_out).parent_path());
    ra::util::write_file_atomic(json_out, out.dump(1) + "\n");
  }
  return 0;
}
