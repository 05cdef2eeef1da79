// `make bench`: the cost of finding every lit pixel, side by side in one run, per platform, kind,
// window and field of view (median microseconds per primitive over interleaved rounds):
//   floor    draw + glFinish only: what the renderer itself must spend for one primitive alone
//            (Vulkan: record + submit + fence wait, the same measure as its render_us);
//   batched  64 primitives drawn under one glFinish, nothing read back: the same floor when the
//            flush is shared, as `run` shares it among small primitives;
//   naive    full-window clear + draw + glFinish + full-window glReadPixels (the paper's method);
//   region   the project's readback one primitive at a time: draw in the primitive's own colour,
//            occlusion query, region glReadPixels (and its metrics, without the reference);
//   project  everything `renderaudit run` does (measure_cases: small primitives batched under one
//            proof, ideal geometry, metrics, reference rasterizer comparison, conformance verdict
//            on the platform's measured effective subpixel grid);
//   unjudged the same without the conformance verdict: project / unjudged - 1 is its cost;
//   layered  project with overlapping lines and triangles drawn together, each in its own layer
//            of the window (platforms/layer_packing.h), on every device (`run` layers only where
//            the device's clock times each primitive: GPUs).
// Mesa picks its driver once per process, so each platform is measured in a child process
// (`readback_bench --platform P`), one per platform and round, the platforms alternating; the
// parent gathers the rows into one table (and EGL / OSMesa ratios) and a JSON file.
#include <cerrno>
#include <filesystem>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "runner/case_measurement.h"
#include "runner/effective_subpixel.h"
#include "rundir/experiment.h"
#include "rundir/manifest.h"
#include "platforms/platform.h"
#include "platforms/raster_device.h"
#include "stats/descriptive.h"
#include "util/child_process.h"

using namespace ra;
using Clock = std::chrono::steady_clock;

namespace {

struct Options {
  std::string platform;  // empty: parent mode
  std::string json_path = "outputs/bench/readback.json";
  int primitives = 1000;  // per configuration and round
  int rounds = 3;
  // OSMesa and EGL on the same drivers, so that the back ends' costs are compared side by side
  // and lavapipe through Vulkan beside llvmpipe through EGL: the same rasterizer core
  std::vector<std::string> platforms = {"osmesa-llvmpipe", "egl-llvmpipe", "osmesa-softpipe",
                                        "egl-softpipe", "vk-lavapipe"};
};

// The analysis stage's median (stats/descriptive.h); 0 for no timings.
double median(const std::vector<double>& v) { return v.empty() ? 0 : stats::median(v); }

ra::geometry::View bench_view(double fov, int window) {
  return ra::geometry::make_view(fov, window, window, 0.01, 10.0,
                                 ra::geometry::random_rotation(2008, 1));
}

// Primitives per call of measure_cases, as `renderaudit run` calls it (in chunks of its own).
constexpr int kChunk = 64;

double mean(const std::vector<double>& v) {
  double sum = 0;
  for (double x : v) sum += x;
  return v.empty() ? 0 : sum / double(v.size());
}

struct Timings {
  std::map<std::string, std::vector<double>> per_primitive;  // floor, naive, region, project
};

nlohmann::json summary_row(const std::string& platform, ra::geometry::Kind kind, int window,
                           double fov, int primitives, const Timings& t) {
  nlohmann::json row = {{"platform", platform},
                        {"kind", ra::geometry::kind_name(kind)},
                        {"window", window},
                        {"fov_deg", fov},
                        {"primitives", primitives}};
  for (const char* m : {"floor", "batched", "naive", "region", "project", "unjudged", "layered"}) {
    row[std::string(m) + "_us"] = median(t.per_primitive.at(m));
    row[std::string(m) + "_mean_us"] = mean(t.per_primitive.at(m));
  }
  return row;
}

// The aliased GL and Vulkan platforms: the readback this benchmark compares.
bool benchable(const std::string& name) {
  const std::optional<ra::rundir::PlatformSpec> spec = ra::rundir::find_platform(name);
  return spec && spec->draws_with_driver() && spec->samples == 0;
}

// `layered`: overlapping primitives share batches in the window's layers on every device (run
// layers them only where the device's clock times each primitive).
std::unique_ptr<ra::platforms::Platform> create_bench_platform(
    const ra::rundir::PlatformSpec& spec, ra::platforms::ReadbackMethod method,
    bool layered = false) {
  ra::platforms::BatchOptions batching;
  if (layered) batching.max_layers = ra::platforms::kMaxLayers;
  return spec.draws_with_vulkan()
             ? ra::platforms::create_vulkan_platform(spec, method, {}, batching)
             : ra::platforms::create_gl_platform(spec, method, {}, batching);
}

// One platform, in this process: prints one JSON object per configuration on stdout, and per
// kind and window one pooled over both fields of view (fov_deg 0).
int measure_platform(const Options& opt) {
  const std::optional<ra::rundir::PlatformSpec> spec =
      ra::rundir::find_platform(opt.platform);
  if (!benchable(opt.platform)) {  // the aliased readback only
    std::fprintf(stderr, "readback_bench: not an aliased GL or Vulkan platform: %s\n",
                 opt.platform.c_str());
    return 2;
  }
  const char* methods[] = {"floor", "naive", "region", "project", "batched", "layered"};
  // The grid `run`'s workers would measure (runner/effective_subpixel.h).
  ra::geometry::SubpixelGrid effective;
  {
    auto probe = create_bench_platform(*spec, ra::platforms::ReadbackMethod::kRegionWithProof);
    probe->set_view(bench_view(30, 128));  // context made and shaders compiled: not timed below
    const auto t0 = Clock::now();
    effective = ra::runner::measure_effective_subpixel(*probe).grid;
    std::printf(
        "%s: effective subpixel grid %s, measured in %.1f ms (every worker of `run` "
        "pays this once)\n",
        opt.platform.c_str(), ra::geometry::subpixel_grid_text(effective).c_str(),
        std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  for (ra::geometry::Kind kind :
       {ra::geometry::Kind::kPoint, ra::geometry::Kind::kLine, ra::geometry::Kind::kTriangle}) {
    for (int window : {128, 907}) {
      Timings pooled;
      for (double fov : {30.0, 150.0}) {
        const ra::geometry::View view = bench_view(fov, window);
        Timings t;
        for (int round = 0; round < opt.rounds; ++round) {
          std::vector<ra::geometry::Primitive> prims;
          for (int i = 0; i < opt.primitives; ++i)
            prims.push_back(
                ra::geometry::make_primitive(2008, kind, uint64_t(round) * opt.primitives + i));
          for (int m = 0; m < 6; ++m) {  // interleaved: every method in every round
            const ra::platforms::ReadbackMethod rm =
                m == 0 || m == 4 ? ra::platforms::ReadbackMethod::kDrawOnly
                : m == 1         ? ra::platforms::ReadbackMethod::kFullWindow
                                 : ra::platforms::ReadbackMethod::kRegionWithProof;
            auto platform = create_bench_platform(*spec, rm, m == 5);
            platform->set_view(view);
            // Mesa compiles its shaders on the first draws, single and batched (the first batch
            // cost 8 ms on llvmpipe): keep that out of the timings.
            std::vector<ra::geometry::Primitive> warm;
            for (uint64_t w = 0; w < kChunk; ++w)
              warm.push_back(ra::geometry::make_primitive(7, kind, w));
            for (uint64_t w = 0; w < 16; ++w)
              platform->render(warm[w], ra::geometry::PixelRect{0, 0, window, window});
            ra::runner::measure_cases(opt.platform, *platform, view, warm, true);
            if (m == 4) {  // the floor with the flush shared by kChunk primitives
              std::vector<double>& us = t.per_primitive["batched"];
              for (size_t i = 0; i < prims.size(); i += kChunk) {
                const std::vector<ra::geometry::Primitive> chunk(
                    prims.begin() + i, prims.begin() + std::min(prims.size(), i + kChunk));
                for (const ra::platforms::RenderResult& r : platform->render_batch(
                         chunk, std::vector<ra::geometry::PixelRegion>(chunk.size())))
                  us.push_back(r.render_us);
              }
              continue;
            }
            if (m == 5) {  // what `run` does, with every device's layers
              ra::runner::CaseComparison judged(true, effective);
              judged.line_rule = ra::runner::line_rule_for(*spec, platform->driver_info());
              for (size_t i = 0; i < prims.size(); i += kChunk) {
                const std::vector<ra::geometry::Primitive> chunk(
                    prims.begin() + i, prims.begin() + std::min(prims.size(), i + kChunk));
                std::vector<double> cost;
                ra::runner::measure_cases(opt.platform, *platform, view, chunk, judged, &cost);
                std::vector<double>& us = t.per_primitive["layered"];
                us.insert(us.end(), cost.begin(), cost.end());
              }
              continue;
            }
            if (m == 3) {
              // Exactly what `renderaudit run` does, chunk by chunk, with and without the
              // conformance verdict on the same platform, chunk by chunk, the order alternating:
              // the two are compared side by side, not across rounds.
              ra::runner::CaseComparison judged(true, effective), unjudged(true, effective);
              unjudged.conformance = false;
              judged.line_rule = unjudged.line_rule =
                  ra::runner::line_rule_for(*spec, platform->driver_info());
              for (size_t i = 0; i < prims.size(); i += kChunk) {
                const std::vector<ra::geometry::Primitive> chunk(
                    prims.begin() + i, prims.begin() + std::min(prims.size(), i + kChunk));
                for (int k = 0; k < 2; ++k) {
                  const bool judge = (k == 0) == ((i / kChunk) % 2 == 0);
                  std::vector<double> cost;
                  ra::runner::measure_cases(opt.platform, *platform, view, chunk,
                                             judge ? judged : unjudged, &cost);
                  std::vector<double>& us = t.per_primitive[judge ? "project" : "unjudged"];
                  us.insert(us.end(), cost.begin(), cost.end());
                }
              }
              continue;
            }
            std::vector<double>& us = t.per_primitive[methods[m]];
            for (const ra::geometry::Primitive& prim : prims) {
              const auto t0 = Clock::now();
              if (m == 2) {
                // One primitive at a time with its own proof: the readback without batching.
                ra::runner::measure_case(opt.platform, *platform, view, prim, false);
              } else {
                platform->render(prim, {});
              }
              us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
            }
          }
        }
        for (const auto& [m, v] : t.per_primitive)
          pooled.per_primitive[m].insert(pooled.per_primitive[m].end(), v.begin(), v.end());
        std::printf("%s\n", summary_row(opt.platform, kind, window, fov,
                                        opt.primitives * opt.rounds, t).dump().c_str());
        std::fflush(stdout);
      }
      std::printf("%s\n", summary_row(opt.platform, kind, window, 0,
                                      2 * opt.primitives * opt.rounds, pooled).dump().c_str());
      std::fflush(stdout);
    }
  }
  return 0;
}

int run_children(const Options& opt, const char* self) {
  std::vector<nlohmann::json> rows;
  for (const auto& p : opt.platforms) {
    if (!benchable(p)) {  // checked before anything runs
      std::fprintf(stderr,
                   "readback_bench: --platforms: '%s' is not an aliased GL or Vulkan "
                   "platform (allowed: %s, vk-lavapipe, vk-lavapipe-bresenham, vk-device:N)\n",
                   p.c_str(), ra::rundir::aliased_gl_platform_names().c_str());
      return 2;
    }
  }
  // One process per platform and round (Mesa picks its driver once per process), the platforms
  // alternating round by round so that a noisy stretch of the machine falls on all of them; each
  // configuration's figure is the median of its rounds' medians. A platform that cannot draw here
  // (no EGL, no device) is left out with a note.
  std::map<std::string, std::vector<nlohmann::json>> by_config;  // platform/kind/window/fov
  std::vector<std::string> key_order;
  std::set<std::string> unavailable;
  for (int round = 0; round < opt.rounds; ++round) {
    for (const auto& p : opt.platforms) {
      if (unavailable.count(p)) continue;
      ra::util::ChildSpec spec;
      spec.argv = {self, "--platform", p, "--primitives", std::to_string(opt.primitives),
                   "--rounds", "1"};
      spec.stdin_null = true;
      const ra::util::ProgramResult measured =
          ra::util::run_program(spec);  // stdout and stderr, interleaved
      const int status = measured.status;
      if (!(WIFEXITED(status) && WEXITSTATUS(status) == 0)) {
        std::fprintf(stderr, "readback_bench: %s left out: measuring it failed (%s): %s\n",
                     p.c_str(), ra::util::describe_exit_status(status).c_str(),
                     measured.output.c_str());
        unavailable.insert(p);
        continue;
      }
      std::stringstream lines(measured.output);
      for (std::string line; std::getline(lines, line);) {
        if (line.empty() || line[0] != '{') {
          if (!line.empty()) std::fprintf(stderr, "%s\n", line.c_str());  // the child's messages
          continue;
        }
        const nlohmann::json row = nlohmann::json::parse(line);
        const std::string key = row["platform"].get<std::string>() + "/" +
                                row["kind"].get<std::string>() + "/" + row["window"].dump() + "/" +
                                row["fov_deg"].dump();
        if (!by_config.count(key)) key_order.push_back(key);
        by_config[key].push_back(row);
      }
    }
  }
  for (const std::string& key : key_order) {
    const std::vector<nlohmann::json>& rounds = by_config[key];
    nlohmann::json row = rounds.front();
    row["primitives"] = rounds.front()["primitives"].get<int>() * int(rounds.size());
    for (auto it = row.begin(); it != row.end(); ++it) {
      if (it.key().size() < 3 || it.key().compare(it.key().size() - 3, 3, "_us") != 0) continue;
      std::vector<double> v;
      for (const nlohmann::json& r : rounds) v.push_back(r[it.key()].get<double>());
      *it = median(v);
    }
    rows.push_back(row);
  }
  std::printf(
      "Microseconds per primitive, %d primitives x %d rounds (one process per platform and round,\n"
      "platforms alternating) per field of view ('both'\n"
      "pools the two). region: the project's readback and metrics one primitive at a time; project:\n"
      "what `run` spends per primitive (its batch's drawing and proof shared equally, plus its own\n"
      "geometry, metrics, reference comparison and conformance verdict); batched: the floor with\n"
      "one glFinish per %d primitives; verdict: what the conformance verdict adds to project\n"
      "(project / project without it - 1, of means); layered: project with overlapping lines and\n"
      "triangles drawn together in layers of the window, on every device. ratios: of medians, and\n"
      "naive/project and layered/project of means.\n",
      opt.primitives, opt.rounds, kChunk);
  std::printf("%-16s %-9s %6s %5s %8s %8s %8s %8s %8s %8s %8s %8s %7s %7s %8s %8s\n", "platform",
              "kind", "window", "fov", "floor", "batched", "naive", "region", "project", "layered",
              "floor", "project", "project", "naive", "verdict", "layered");
  std::printf("%-16s %-9s %6s %5s %8s %8s %8s %8s %8s %8s %8s %8s %7s %7s %8s %8s\n", "", "", "", "",
              "median", "median", "median", "median", "median", "median", "mean", "mean", "/floor",
              "/proj", "cost", "/proj");
  for (const auto& r : rows) {
    const double fov = r["fov_deg"];
    const std::string fov_text = fov == 0 ? "both" : std::to_string(int(fov));
    const double floor = r["floor_us"], project = r["project_us"];
    const double verdict_cost =
        r["project_mean_us"].get<double>() / r["unjudged_mean_us"].get<double>() - 1;
    std::printf(
        "%-16s %-9s %6d %5s %8.1f %8.1f %8.1f %8.1f %8.1f %8.1f %8.1f %8.1f %7.2f %7.1f %7.1f%% "
        "%8.2f\n",
        r["platform"].get<std::string>().c_str(), r["kind"].get<std::string>().c_str(),
        r["window"].get<int>(), fov_text.c_str(), floor, r["batched_us"].get<double>(),
        r["naive_us"].get<double>(), r["region_us"].get<double>(), project,
        r["layered_us"].get<double>(), r["floor_mean_us"].get<double>(),
        r["project_mean_us"].get<double>(), project / floor,
        r["naive_mean_us"].get<double>() / r["project_mean_us"].get<double>(), 100 * verdict_cost,
        r["layered_mean_us"].get<double>() / r["project_mean_us"].get<double>());
  }
  // EGL against OSMesa on the same driver: the back end's own cost
  bool header = false;
  for (const auto& egl : rows) {
    const std::string name = egl["platform"];
    if (name.rfind("egl-", 0) != 0) continue;
    for (const auto& os : rows) {
      if (os["platform"] != "osmesa-" + name.substr(4) || os["kind"] != egl["kind"] ||
          os["window"] != egl["window"] || os["fov_deg"] != egl["fov_deg"] || os["fov_deg"] != 0)
        continue;
      if (!header) {
        std::printf("\nEGL / OSMesa on the same driver (medians, both fields of view pooled):\n");
        std::printf("%-16s %-9s %6s %9s %9s %9s\n", "platform", "kind", "window", "floor",
                    "batched", "project");
        header = true;
      }
      std::printf("%-16s %-9s %6d %9.3f %9.3f %9.3f\n", name.c_str(),
                  egl["kind"].get<std::string>().c_str(), egl["window"].get<int>(),
                  egl["floor_us"].get<double>() / os["floor_us"].get<double>(),
                  egl["batched_us"].get<double>() / os["batched_us"].get<double>(),
                  egl["project_us"].get<double>() / os["project_us"].get<double>());
    }
  }
  const std::filesystem::path dir = std::filesystem::path(opt.json_path).parent_path();
  if (!dir.empty()) std::filesystem::create_directories(dir);
  nlohmann::json doc = ra::rundir::document_header("bench-readback", 1, false);
  doc["benchmark"] = "readback";
  doc["rows"] = rows;
  std::ofstream(opt.json_path) << doc.dump(2) << "\n";
  std::printf("JSON: %s\n", opt.json_path.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "readback_bench: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--platform") opt.platform = value();
    else if (a == "--json") opt.json_path = value();
    else if (a == "--platforms") {
      opt.platforms.clear();
      std::stringstream list(value());
      for (std::string p; std::getline(list, p, ',');) opt.platforms.push_back(p);
    }
    else if (a == "--primitives") opt.primitives = std::max(1, std::stoi(value()));
    else if (a == "--rounds") opt.rounds = std::max(1, std::stoi(value()));
    else {
      std::fprintf(stderr,
                   "usage: readback_bench [--primitives N] [--rounds R] [--json FILE] [--platforms P,Q]\n");
      return 2;
    }
  }
  if (!opt.platform.empty()) return measure_platform(opt);
  return run_children(opt, argv[0]);
}
