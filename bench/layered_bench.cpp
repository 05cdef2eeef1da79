// `layered_bench --platform P [--experiment experiments/nist2008.toml] [--primitives N]`: layered
// batches (platforms/layer_packing.h) against primitives drawn without layers, side by side on
// one platform, over every view of an experiment and N primitives per kind and view (default
// 10,000: one nist2008 shard of each). Two platform objects of the same driver in this process:
// one with a single layer (what `run` does on the CPU drivers), one with as many layers as the
// device gives (what `run` does on a GPU with a timer). Each chunk of 640 primitives is measured by
// both, the order alternating chunk by chunk, exactly as `run` measures (measure_cases).
//
// Printed per kind and window: records equal in every column but the timing ones (must be all),
// the wall time per primitive each way and their ratio, primitives per second layered, and the
// medians of render_us and host_us each way with the clock each reads. One platform per process:
// Mesa picks its driver when the first context is made.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "platforms/platform.h"
#include "platforms/raster_device.h"
#include "runner/case_measurement.h"
#include "runner/effective_subpixel.h"
#include "rundir/experiment.h"
#include "stats/descriptive.h"
#include "util/errors.h"

using namespace ra;

namespace {

using Clock = std::chrono::steady_clock;
constexpr size_t kChunk = 640;

std::unique_ptr<platforms::Platform> make(const rundir::PlatformSpec& spec, int max_layers) {
  platforms::BatchOptions batching;
  batching.max_layers = max_layers;
  return spec.draws_with_vulkan()
             ? platforms::create_vulkan_platform(spec, platforms::ReadbackMethod::kRegionWithProof,
                                                 {}, batching)
             : platforms::create_gl_platform(spec, platforms::ReadbackMethod::kRegionWithProof, {},
                                             batching);
}

struct Way {
  double wall_s = 0;
  std::vector<double> render_us, host_us;
  std::string clock;
};
struct Cell {
  uint64_t records = 0, equal = 0;
  Way single, layered;
};

double median(const std::vector<double>& v) { return v.empty() ? 0 : stats::median(v); }

}  // namespace

int main(int argc, char** argv) {
  std::string platform_name, experiment_path = "experiments/nist2008.toml";
  uint64_t per_kind = 10000;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&] { return i + 1 < argc ? std::string(argv[++i]) : std::string(); };
    if (a == "--platform") platform_name = next();
    else if (a == "--experiment") experiment_path = next();
    else if (a == "--primitives") per_kind = std::stoull(next());
    else {
      std::fprintf(stderr,
                   "usage: layered_bench --platform P [--experiment FILE] [--primitives N]\n");
      return 2;
    }
  }
  const std::optional<rundir::PlatformSpec> spec = rundir::find_platform(platform_name);
  if (!spec || !spec->draws_with_driver() || spec->samples > 0) {
    std::fprintf(stderr, "layered_bench: --platform: '%s' is not an aliased GL or Vulkan platform\n",
                 platform_name.c_str());
    return 2;
  }
  try {
    const rundir::Experiment exp = rundir::load_experiment(experiment_path);
    auto single = make(*spec, 1);
    auto layered = make(*spec, platforms::kMaxLayers);
    single->set_view(exp.views.front());
    runner::CaseComparison comparison(true, runner::measure_effective_subpixel(*single).grid);
    comparison.line_rule = runner::line_rule_for(*spec, single->driver_info());
    std::map<std::pair<int, int>, Cell> cells;  // (kind, window)
    const auto t_all = Clock::now();
    for (const geometry::View& view : exp.views) {
      single->set_view(view);
      layered->set_view(view);
      for (geometry::Kind kind :
           {geometry::Kind::kPoint, geometry::Kind::kLine, geometry::Kind::kTriangle}) {
        Cell& cell = cells[{int(kind), view.width}];
        const uint64_t n = std::min<uint64_t>(per_kind, exp.counts[size_t(kind)]);
        for (uint64_t begin = 0; begin < n; begin += kChunk) {
          std::vector<geometry::Primitive> prims;
          for (uint64_t i = begin; i < std::min(n, begin + kChunk); ++i)
            prims.push_back(geometry::make_primitive(exp.seed, kind, i));
          std::vector<metrics::Record> a, b;
          for (int k = 0; k < 2; ++k) {
            const bool layered_now = (k == 0) == ((begin / kChunk) % 2 == 0);
            const auto t0 = Clock::now();
            (layered_now ? b : a) = runner::measure_cases(
                platform_name, layered_now ? *layered : *single, view, prims, comparison);
            (layered_now ? cell.layered : cell.single).wall_s +=
                std::chrono::duration<double>(Clock::now() - t0).count();
          }
          for (size_t i = 0; i < prims.size(); ++i) {
            ++cell.records;
            const std::string one = metrics::untimed_record_line(a[i]);
            const std::string many = metrics::untimed_record_line(b[i]);
            if (one == many) ++cell.equal;
            else if (cell.records - cell.equal <= 3)
              std::fprintf(stderr, "differs: view %d %s %llu\n  %s  %s", view.id,
                           geometry::kind_name(kind), (unsigned long long)prims[i].index,
                           one.c_str(), many.c_str());
            if (a[i].status != metrics::CaseStatus::kOk) continue;
            for (auto [way, r] : {std::pair{&cell.single, &a[i]}, std::pair{&cell.layered, &b[i]}}) {
              way->render_us.push_back(r->render_us);
              way->host_us.push_back(r->host_us);
              way->clock = r->clock;
            }
          }
        }
      }
    }
    std::printf(
        "%s (%s), %s, up to %llu primitives per kind and view, chunks of %zu, %.0f s in all.\n"
        "wall: microseconds per primitive of measure_cases (everything `run` does per primitive);\n"
        "render_us and host_us: medians; layers: %d at 128 x 128, %d at 907 x 907 at most.\n",
        platform_name.c_str(), single->driver_info().renderer.c_str(), experiment_path.c_str(),
        (unsigned long long)per_kind, kChunk,
        std::chrono::duration<double>(Clock::now() - t_all).count(),
        platforms::layers_for_window(128, 128, platforms::kMaxLayers),
        platforms::layers_for_window(907, 907, platforms::kMaxLayers));
    std::printf("%-9s %6s %8s %9s %9s %9s %7s %10s %18s %18s %12s\n", "kind", "window", "records",
                "identical", "wall 1", "wall L", "L / 1", "prims/s L", "render_us 1 / L",
                "host_us 1 / L", "clock 1 / L");
    int status = 0;
    for (const auto& [key, c] : cells) {
      const double per1 = c.single.wall_s * 1e6 / double(c.records);
      const double perL = c.layered.wall_s * 1e6 / double(c.records);
      std::printf("%-9s %6d %8llu %9llu %9.1f %9.1f %7.2f %10.0f %8.1f / %7.1f %8.1f / %7.1f %5s / %s\n",
                  geometry::kind_name(geometry::Kind(key.first)), key.second,
                  (unsigned long long)c.records, (unsigned long long)c.equal, per1, perL,
                  perL / per1, double(c.records) / c.layered.wall_s, median(c.single.render_us),
                  median(c.layered.render_us), median(c.single.host_us), median(c.layered.host_us),
                  c.single.clock.c_str(), c.layered.clock.c_str());
      if (c.equal != c.records) status = 1;
    }
    if (status) std::printf("NOT IDENTICAL: layered records differ from single-layer ones\n");
    return status;
  } catch (const util::UserError& e) {
    std::fprintf(stderr, "layered_bench: %s\n", e.what());
    return 2;
  }
}
