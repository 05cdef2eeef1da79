// `layered_bench --platform P [--experiment experiments/nist2008.toml] [--primitives N]
// [--versus layers|scan]`: two ways of measuring side by side on one platform, over every view of
// an experiment and N primitives per kind and view (default 10,000: one nist2008 shard of each).
// --versus layers (the default): layered batches (platforms/layer_packing.h) against primitives
// drawn without layers: one platform object with a single layer (what `run` does on the CPU
// drivers, column 1), one with as many layers as the device gives (what `run` does on a GPU with
// a timer, column L). --versus scan: both layered, the lit pixels found on the host over the
// pixels read back (column H, what `run` does) or on the device (column D: a compute pass sends a
// bit per pixel, platforms/lit_mask.h). Each chunk of 640 primitives is measured both ways, the
// order alternating chunk by chunk, exactly as `run` measures (measure_cases).
//
// Printed per kind and window: records equal in every column but the timing ones (must be all),
// the wall time per primitive each way and their ratio, primitives per second layered, and the
// medians of render_us and host_us each way with the clock each reads; then where each way's time
// went (Platform::stage_times: drawing, the device's own time, transfer, host scan, the rest).
// One platform per process: Mesa picks its driver when the first context is made.
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

std::unique_ptr<platforms::Platform> make(const rundir::PlatformSpec& spec, int max_layers,
                                          bool device_scan) {
  platforms::BatchOptions batching;
  batching.max_layers = max_layers;
  if (device_scan) batching.scan = platforms::BatchOptions::Scan::kDevice;
  return spec.draws_with_vulkan()
             ? platforms::create_vulkan_platform(spec, platforms::ReadbackMethod::kRegionWithProof,
                                                 {}, batching)
             : platforms::create_gl_platform(spec, platforms::ReadbackMethod::kRegionWithProof, {},
                                             batching);
}

struct Way {
  double wall_s = 0;
  platforms::StageTimes stages;  // summed over the cell's chunks, microseconds
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
  std::string versus = "layers";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&] { return i + 1 < argc ? std::string(argv[++i]) : std::string(); };
    if (a == "--platform") platform_name = next();
    else if (a == "--experiment") experiment_path = next();
    else if (a == "--primitives") per_kind = std::stoull(next());
    else if (a == "--versus") versus = next();
    else {
      versus = "";
      break;
    }
  }
  if (versus != "layers" && versus != "scan") {
    std::fprintf(stderr,
                 "usage: layered_bench --platform P [--experiment FILE] [--primitives N] "
                 "[--versus layers|scan]\n");
    return 2;
  }
  const bool by_scan = versus == "scan";
  const char* a_name = by_scan ? "H" : "1";  // the columns' names
  const char* b_name = by_scan ? "D" : "L";
  const std::optional<rundir::PlatformSpec> spec = rundir::find_platform(platform_name);
  if (!spec || !spec->draws_with_driver() || spec->samples > 0) {
    std::fprintf(stderr, "layered_bench: --platform: '%s' is not an aliased GL or Vulkan platform\n",
                 platform_name.c_str());
    return 2;
  }
  try {
    const rundir::Experiment exp = rundir::load_experiment(experiment_path);
    auto single = make(*spec, by_scan ? platforms::kMaxLayers : 1, false);
    auto layered = make(*spec, platforms::kMaxLayers, by_scan);
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
            platforms::Platform& platform = layered_now ? *layered : *single;
            Way& way = layered_now ? cell.layered : cell.single;
            const platforms::StageTimes before = platform.stage_times();
            const auto t0 = Clock::now();
            (layered_now ? b : a) =
                runner::measure_cases(platform_name, platform, view, prims, comparison);
            way.wall_s += std::chrono::duration<double>(Clock::now() - t0).count();
            const platforms::StageTimes after = platform.stage_times();
            way.stages.draw_us += after.draw_us - before.draw_us;
            way.stages.device_us += after.device_us - before.device_us;
            way.stages.transfer_us += after.transfer_us - before.transfer_us;
            way.stages.host_scan_us += after.host_scan_us - before.host_scan_us;
            way.stages.results_us += after.results_us - before.results_us;
            way.stages.clear_us += after.clear_us - before.clear_us;
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
        "render_us and host_us: medians; layers: %d at 128 x 128, %d at 907 x 907 at most.\n"
        "%s\n",
        platform_name.c_str(), single->driver_info().renderer.c_str(), experiment_path.c_str(),
        (unsigned long long)per_kind, kChunk,
        std::chrono::duration<double>(Clock::now() - t_all).count(),
        platforms::layers_for_window(128, 128, platforms::kMaxLayers),
        platforms::layers_for_window(907, 907, platforms::kMaxLayers),
        by_scan ? "H: layered, lit pixels found on the host; D: layered, found on the device."
                : "1: one layer; L: layered; both find lit pixels on the host.");
    auto pair = [&](const char* what) {
      return std::string(what) + " " + a_name + " / " + b_name;
    };
    std::printf("%-9s %6s %8s %9s %9s %9s %7s %10s %18s %18s %12s\n", "kind", "window", "records",
                "identical", (std::string("wall ") + a_name).c_str(),
                (std::string("wall ") + b_name).c_str(),
                (std::string(b_name) + " / " + a_name).c_str(),
                (std::string("prims/s ") + b_name).c_str(), pair("render_us").c_str(),
                pair("host_us").c_str(), pair("clock").c_str());
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
    std::printf(
        "\nWhere the time went, microseconds per primitive (host clock; device: what the device's\n"
        "timestamps saw of the drawing, where it timed it): drawing = recording, submission and the\n"
        "wait; transfer = copies to the host or the scan on the device, and their waits; host scan =\n"
        "finding lit pixels in what came back; results = fetching counts and timestamps; clear =\n"
        "clearing the window; rest = the reference rasterizer, metrics, upkeep.\n");
    std::printf("%-9s %6s %4s %9s %9s %9s %9s %9s %9s %9s %9s\n", "kind", "window", "way", "wall",
                "drawing", "device", "transfer", "host scan", "results", "clear", "rest");
    for (const auto& [key, c] : cells)
      for (const auto& [name, way] : {std::pair{a_name, &c.single}, std::pair{b_name, &c.layered}}) {
        const double n = double(c.records);
        const platforms::StageTimes& t = way->stages;
        const double wall = way->wall_s * 1e6 / n;
        std::printf("%-9s %6d %4s %9.1f %9.1f %9.1f %9.1f %9.1f %9.1f %9.1f %9.1f\n",
                    geometry::kind_name(geometry::Kind(key.first)), key.second, name, wall,
                    t.draw_us / n, t.device_us / n, t.transfer_us / n, t.host_scan_us / n,
                    t.results_us / n, t.clear_us / n,
                    wall - (t.draw_us + t.transfer_us + t.host_scan_us + t.results_us +
                            t.clear_us) / n);
      }
    if (status) std::printf("NOT IDENTICAL: the records of %s differ from those of %s\n", b_name, a_name);
    return status;
  } catch (const util::UserError& e) {
    std::fprintf(stderr, "layered_bench: %s\n", e.what());
    return 2;
  }
}
