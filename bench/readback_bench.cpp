// `make bench`: the cost of finding every lit pixel, side by side in one run, per platform, kind,
// window and field of view (median microseconds per primitive over interleaved rounds):
//   floor    draw + glFinish only: what the renderer itself must spend;
//   naive    full-window clear + draw + glFinish + full-window glReadPixels (the paper's method);
//   region   the project's readback: scissored clear, draw, occlusion query, region glReadPixels;
//   project  everything `renderaudit run` does per primitive (region readback, ideal geometry,
//            metrics, reference rasterizer comparison).
// Mesa picks its driver once per process, so each platform is measured in a child process
// (`readback_bench --platform P`) and the parent gathers the rows into one table and a JSON file.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "runner/case_measurement.h"
#include "runner/experiment.h"
#include "runner/platform.h"

using namespace ra;
using Clock = std::chrono::steady_clock;

namespace {

struct Options {
  std::string platform;  // empty: parent mode
  std::string json_path = "outputs/bench/readback.json";
  int primitives = 1000;  // per configuration and round
  int rounds = 3;
  std::vector<std::string> platforms = {"osmesa-llvmpipe", "osmesa-softpipe"};
};

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

View bench_view(double fov, int window) {
  return make_view(fov, window, window, 0.01, 10.0, random_rotation(2008, 1));
}

// One platform, in this process: prints one JSON object per configuration on stdout.
int measure_platform(const Options& opt) {
  const PlatformSpec* spec = find_platform(opt.platform);
  if (!spec || !spec->gallium_driver) {
    std::fprintf(stderr, "readback_bench: not an OSMesa platform: %s\n", opt.platform.c_str());
    return 2;
  }
  const char* methods[] = {"floor", "naive", "region", "project"};
  for (Kind kind : {Kind::kPoint, Kind::kLine, Kind::kTriangle}) {
    for (int window : {128, 907}) {
      for (double fov : {30.0, 150.0}) {
        const View view = bench_view(fov, window);
        std::map<std::string, std::vector<double>> us;
        uint64_t full_scans = 0, project_total = 0;
        for (int round = 0; round < opt.rounds; ++round) {
          for (int m = 0; m < 4; ++m) {
            const ReadbackMethod rm = m == 0   ? ReadbackMethod::kDrawOnly
                                      : m == 1 ? ReadbackMethod::kFullWindow
                                               : ReadbackMethod::kRegionWithProof;
            auto platform = create_osmesa_platform(*spec, rm);
            platform->set_view(view);
            for (int i = 0; i < opt.primitives; ++i) {
              const Primitive prim = make_primitive(2008, kind, uint64_t(round) * opt.primitives + i);
              const auto t0 = Clock::now();
              if (m == 3) {
                measure_case(opt.platform, *platform, view, prim, true);
              } else if (m == 2) {
                // Same region as `run` computes, so the readback cost is the project's.
                const Record r = measure_case(opt.platform, *platform, view, prim, false);
                (void)r;
              } else {
                platform->render(prim, {});
              }
              us[methods[m]].push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
            }
          }
        }
        (void)full_scans;
        (void)project_total;
        nlohmann::json row = {{"platform", opt.platform}, {"kind", kind_name(kind)},
                              {"window", window},         {"fov_deg", fov},
                              {"primitives", opt.primitives * opt.rounds}};
        for (const char* m : methods) row[std::string(m) + "_us"] = median(us[m]);
        std::printf("%s\n", row.dump().c_str());
        std::fflush(stdout);
      }
    }
  }
  return 0;
}

int run_children(const Options& opt, const char* self) {
  std::vector<nlohmann::json> rows;
  for (const auto& p : opt.platforms) {
    const std::string cmd = std::string(self) + " --platform " + p + " --primitives " +
                            std::to_string(opt.primitives) + " --rounds " + std::to_string(opt.rounds);
    FILE* pipe = ::popen(cmd.c_str(), "r");
    char line[4096];
    while (std::fgets(line, sizeof line, pipe)) rows.push_back(nlohmann::json::parse(line));
    if (::pclose(pipe) != 0) {
      std::fprintf(stderr, "readback_bench: measuring %s failed\n", p.c_str());
      return 1;
    }
  }
  std::printf("Median microseconds per primitive (%d primitives x %d interleaved rounds each)\n",
              opt.primitives, opt.rounds);
  std::printf("%-16s %-9s %6s %5s %9s %9s %9s %9s %13s %13s\n", "platform", "kind", "window", "fov",
              "floor", "naive", "region", "project", "project/floor", "naive/project");
  for (const auto& r : rows) {
    const double floor = r["floor_us"], naive = r["naive_us"], project = r["project_us"];
    std::printf("%-16s %-9s %6d %5.0f %9.1f %9.1f %9.1f %9.1f %13.2f %13.2f\n",
                r["platform"].get<std::string>().c_str(), r["kind"].get<std::string>().c_str(),
                r["window"].get<int>(), r["fov_deg"].get<double>(), floor, naive,
                r["region_us"].get<double>(), project, project / floor, naive / project);
  }
  const std::string dir = opt.json_path.substr(0, opt.json_path.rfind('/'));
  if (!dir.empty()) std::system(("mkdir -p " + dir).c_str());
  std::ofstream(opt.json_path) << nlohmann::json({{"schema_version", 1},
                                                   {"benchmark", "readback"},
                                                   {"rows", rows}})
                                      .dump(2)
                               << "\n";
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
    else if (a == "--primitives") opt.primitives = std::max(1, std::stoi(value()));
    else if (a == "--rounds") opt.rounds = std::max(1, std::stoi(value()));
    else {
      std::fprintf(stderr,
                   "usage: readback_bench [--primitives N] [--rounds R] [--json FILE] [--platform P]\n");
      return 2;
    }
  }
  if (!opt.platform.empty()) return measure_platform(opt);
  return run_children(opt, argv[0]);
}
