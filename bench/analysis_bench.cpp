// Benchmark of `renderaudit analyze`: synthesises a run directory of N records (default 2.4
// million: the paper's 100,000 primitives x 8 views x 3 kinds, here spread over 2 platforms) with
// ra::write_record, then times each stage of analyze_run (load, equivalence, tables, figures,
// write), and for comparison ra::read_records (the runner's reference reader) over the same files
// and one Box-Cox lambda fit on a pooled group with and without the subsample.
//
//   analysis_bench [--records N] [--platforms P] [--dir DIR] [--jobs J] [--format F] [--keep]
//
// --format csv.zst (default) or csv: the records files' format (rundir/records_format.h).
//
// The values are random but shaped like the paper's: visibility proportions of its Tables 2, 5, 8;
// PE the distance to a pixel centre with uniform offsets; LSEs small and positive, LSEu near 0.24
// px; TEs with a spike at 0 (full-window renderings at FOV 30), TEu log-normal around 26 px^2 at
// 128 px; render_us log-normal. A directory made earlier with the same N and P is reused
// (DIR/bench.txt records them); --keep leaves it in place afterwards (default: removed).
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/run_analysis.h"
#include "analysis/view_equivalence.h"
#include "rundir/records_reader.h"
#include "rundir/run_folder.h"
#include "util/errors.h"
#include "metrics/records.h"
#include "rundir/records_format.h"
#include "rundir/shard_file.h"

namespace fs = std::filesystem;

namespace {

class Rng {  // splitmix64
 public:
  explicit Rng(std::uint64_t seed) : s_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (s_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return (static_cast<double>(next() >> 11) + 0.5) * 0x1.0p-53; }
  double normal() {
    return std::sqrt(-2 * std::log(uniform())) * std::cos(6.283185307179586 * uniform());
  }

 private:
  std::uint64_t s_;
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

struct Params {
  std::uint64_t records = 2400000;
  int platforms = 2;
  std::string dir = "/tmp/ra_analysis_bench";
  unsigned jobs = 0;
  bool keep = false;
  ra::rundir::RecordsFormat format = ra::rundir::RecordsFormat::kCsvZst;
};

// One synthetic record of a view; the shapes follow the paper's tables.
ra::metrics::Record synth(Rng& rng, const std::string& platform, int p, const char* kind, int view,
                          std::uint64_t index) {
  ra::metrics::Record r;
  r.platform = platform;
  r.view = view;
  const int v0 = view - 1;  // window outermost, orientation innermost (docs/experiments.md)
  r.orientation = v0 % 2 + 1;
  r.fov_deg = (v0 / 2) % 2 ? 150 : 30;
  r.width = r.height = v0 / 4 ? 907 : 128;
  r.view_group = v0 / 2;
  r.near = 0.01;
  r.far = 10;
  r.kind = kind;
  r.index = index;
  const bool wide = r.fov_deg == 150;
  const double norm = r.width;  // sqrt(W*H), square windows
  const std::string k = kind;
  const double p_visible = k == "point"  ? (wide ? 0.3836 : 0.0211)
                           : k == "line" ? (wide ? 0.6263 : 0.1027)
                                         : (wide ? 0.7755 : 0.2629);
  const double u = rng.uniform();
  r.visibility = u < p_visible            ? ra::metrics::Visibility::kTrueVisible
                 : u < p_visible + 0.0005 ? ra::metrics::Visibility::kFalseInvisible
                                          : ra::metrics::Visibility::kTrueInvisible;
  r.render_us = std::exp(std::log(wide ? 3.0 : 2.0) + 0.7 * rng.normal());
  r.pixel_hash = rng.next();
  r.ref_diff = 0;
  if (r.visibility != ra::metrics::Visibility::kTrueVisible) return r;
  if (k == "point") {
    r.pixels = 1;
    r.pe = std::hypot(rng.uniform() - 0.5, rng.uniform() - 0.5);
    r.pe_norm = r.pe / norm;
  } else if (k == "line") {
    r.pixels = 20 + static_cast<std::int64_t>(rng.uniform() * 100);
    r.lse_s = std::fabs((0.004 + 0.03 * p) + (0.01 + 0.02 * p) * rng.normal());
    r.lse_u = std::max(0.01, 0.24 + 0.02 * rng.normal());
    r.extent_error = std::fabs(0.3 * rng.normal());
    r.lse_s_norm = r.lse_s / norm;
    r.lse_u_norm = r.lse_u / norm;
    r.chain_8connected = 1;
    r.gaps = 0;
  } else {
    r.pixels = 100 + static_cast<std::int64_t>(rng.uniform() * 1000);
    const bool full = !wide && rng.uniform() < 0.15;
    r.full_window = full;
    r.simply_connected = 1;
    if (full) {
      r.te_s = r.te_u = r.te_u_edge_norm = 0;
    } else {
      const double scale = norm / 128;
      r.te_u = 26 * scale * std::exp(0.6 * rng.normal());
      r.te_s = (0.5 + 2.0 * p) * scale * rng.normal();
      r.te_u_edge_norm = r.te_u / (100 * scale);
    }
    r.te_s_norm = r.te_s / (norm * norm);
    r.te_u_norm = r.te_u / (norm * norm);
  }
  return r;
}

void synthesise(const Params& prm) {
  const std::string stamp = std::to_string(prm.records) + " " + std::to_string(prm.platforms) +
                            " " + ra::rundir::records_format_name(prm.format);
  std::ifstream old(prm.dir + "/bench.txt");
  std::string line;
  if (old && std::getline(old, line) && line == stamp) {
    std::cout << "reusing " << prm.dir << " (" << stamp << ")\n";
    return;
  }
  fs::remove_all(prm.dir);
  fs::create_directories(ra::rundir::run_folder::records(prm.dir));
  const char* kinds[] = {"point", "line", "triangle"};
  const std::uint64_t per_view = prm.records / (static_cast<std::uint64_t>(prm.platforms) * 3 * 8);
  const std::uint64_t shard = 5000;
  const auto t0 = std::chrono::steady_clock::now();
  std::uint64_t written = 0;
  for (int p = 0; p < prm.platforms; ++p) {
    const std::string platform = "bench-platform-" + std::to_string(p + 1);
    for (int k = 0; k < 3; ++k) {
      for (int view = 1; view <= 8; ++view) {
        Rng rng(0x5EEDull * 1000003u + static_cast<std::uint64_t>(p * 100 + k * 10 + view));
        for (std::uint64_t first = 0; first < per_view; first += shard) {
          const std::uint64_t last = std::min(per_view, first + shard);
          // sealed, as a run writes it (rundir/shard_file.h)
          ra::rundir::RecordsFileWriter out(
              ra::rundir::run_folder::records(prm.dir) + "/" + platform + "." + kinds[k] + ".v" +
                  std::to_string(view) + "." + std::to_string(first) + "-" + std::to_string(last) +
                  ra::rundir::records_extension(prm.format),
              prm.format);
          for (std::uint64_t i = first; i < last; ++i)
            out.write(synth(rng, platform, p, kinds[k], view, i));
          out.finish();
          written += last - first;
        }
      }
    }
  }
  std::ofstream(prm.dir + "/bench.txt") << stamp << "\n";
  std::printf("synthesised %llu records in %s: %.1f s\n", static_cast<unsigned long long>(written),
              prm.dir.c_str(), seconds_since(t0));
}

}  // namespace

int main(int argc, char** argv) {
  Params prm;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "analysis_bench: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--records") {
      prm.records = std::stoull(value());
    } else if (a == "--platforms") {
      prm.platforms = std::stoi(value());
    } else if (a == "--dir") {
      prm.dir = value();
    } else if (a == "--jobs") {
      prm.jobs = static_cast<unsigned>(std::stoul(value()));
    } else if (a == "--format") {
      const std::optional<ra::rundir::RecordsFormat> f =
          ra::rundir::parse_records_format(value());
      if (!f) {
        std::fprintf(stderr, "analysis_bench: --format csv or csv.zst\n");
        return 2;
      }
      prm.format = *f;
    } else if (a == "--keep") {
      prm.keep = true;
    } else {
      std::fprintf(stderr,
                   "usage: analysis_bench [--records N] [--platforms P] [--dir DIR] [--jobs J] "
                   "[--format csv|csv.zst] [--keep]\n");
      return 2;
    }
  }
  if (prm.platforms < 1 || prm.records < static_cast<std::uint64_t>(prm.platforms) * 24) {
    std::fprintf(stderr, "analysis_bench: need at least 24 records per platform\n");
    return 2;
  }
  try {
    synthesise(prm);

    // the reference reader, for comparison with the analysis stage's own
    {
      const auto t0 = std::chrono::steady_clock::now();
      std::uint64_t n = 0;
      for (const auto& e : fs::directory_iterator(ra::rundir::run_folder::records(prm.dir))) {
        if (ra::rundir::is_records_file_name(e.path().filename().string()))
          ra::rundir::read_records(e.path().string(), [&](const ra::metrics::Record&) { ++n; });
      }
      std::printf("ra::read_records (metrics/records.h, one thread): %llu records in %.2f s\n",
                  static_cast<unsigned long long>(n), seconds_since(t0));
    }

    ra::analysis::AnalyzeOptions options;
    options.run_dir = prm.dir;
    options.jobs = prm.jobs;
    options.pixel_pitches_mm = {0.255, 0.294, 1.5};
    const auto t0 = std::chrono::steady_clock::now();
    const ra::analysis::AnalyzeResult r = ra::analysis::analyze_run(options);
    const double total = seconds_since(t0);
    std::printf("analyze_run: %llu records, %zu files written, jobs %u:\n",
                static_cast<unsigned long long>(r.records), r.files.size(), prm.jobs);
    for (const auto& t : r.timings) std::printf("  %-12s %7.2f s\n", t.stage.c_str(), t.seconds);
    std::printf("  %-12s %7.2f s (%.2f M records/s)\n", "total", total,
                static_cast<double>(r.records) / total / 1e6);

    // Box-Cox on one pooled group of 200,000 values: the subsample against every value
    std::vector<double> pooled(200000);
    Rng rng(7);
    for (double& x : pooled) x = std::hypot(rng.uniform() - 0.5, rng.uniform() - 0.5);
    for (std::size_t m : {std::size_t{10000}, std::size_t{20000}, pooled.size()}) {
      ra::analysis::ComparisonOptions c;  // the analysis default: 10000, grid step 0.1
      c.box_cox_subsample = m;
      const auto t1 = std::chrono::steady_clock::now();
      const ra::analysis::BoxCoxFit f = ra::analysis::fit_box_cox(pooled, c);
      std::printf("Box-Cox PPCC fit, 200000 values, lambda chosen on %zu: lambda = %.4f, %.2f s\n",
                  f.n_fit, f.lambda, seconds_since(t1));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "analysis_bench: %s\n", e.what());
    return 1;
  }
  if (!prm.keep) fs::remove_all(prm.dir);
  return 0;
}
