// Which reading of the NIST paper's method reproduces its published numbers? The paper's
// primitives and views are measured on the exact reference rasterizer (no driver: what remains is
// the method) under candidate readings, each set beside the paper's Platform I and II with z:
//
//   near plane   the text's 0.01 against nearer planes (1e-3, 1e-4, 1e-5) for Tables 6, 7, 9, 10
//                and the shares of ideally visible lines and triangles (Tables 5 and 8);
//   triangles    at near 0.01: near-clipped triangles left out, full-window renderings left out,
//                vertices uniform in the cube [-1, 1]^3 instead of the ball, vertices snapped to
//                4 or 8 subpixel bits (8 also for lines: llvmpipe's grid);
//   points       the false-invisible count of Table 2 when points within m pixels outside the
//                window count as lying in the field of view (m = 0, 0.25, 0.5, 1).
//
// Units as in the records: TEu-norm x 10^3, TEs-norm x 10^6, LSEu-norm x 10^3, LSEs-norm x 10^6
// (the paper's scales). Prints Markdown; docs/method.md, "Where we differ from the paper", quotes its output.
// Build: `cmake --build build --target paper_readings`; run: `build/paper_readings [--per-view N]`.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "analysis/paper_values.h"
#include "geometry/clipping.h"
#include "geometry/reference_rasterizer.h"
#include "metrics/line_metrics.h"
#include "metrics/point_metrics.h"
#include "metrics/triangle_metrics.h"
#include "rundir/experiment.h"
#include "stats/bootstrap.h"
#include "stats/descriptive.h"
#include "util/counter_rng.h"
#include "util/errors.h"
#include "util/parallel.h"

namespace ra {
namespace {

// The paper's visibility counts per view group A-D, Platform I (Tables 2, 5, 8; 200,000 primitives
// per group): true-visible and false-invisible.
constexpr double kPaperPerGroup = 200000;
constexpr std::array<double, 4> kPaperPointFalseInvisible = {72, 154, 11, 29};
constexpr std::array<double, 4> kPaperLineVisible = {20540 + 80, 125260 + 184, 20608 + 12,
                                                     125424 + 20};
constexpr std::array<double, 4> kPaperTriangleVisible = {52580 + 287, 155090 + 674, 52828 + 39,
                                                         155691 + 73};

struct Options {
  std::string experiment = "experiments/nist2008.toml";
  std::string paper = "experiments/papers/nist2008-tables.toml";
  uint64_t per_view = 100000;
  int bootstrap = 500;
  unsigned jobs = 0;
};

// One reading: how the primitive is made and measured, and whether it is counted.
struct Reading {
  std::string name;
  double near = 0.01;             // world units
  bool cube_vertices = false;     // uniform in [-1, 1]^3 instead of the unit ball
  geometry::SubpixelGrid grid;    // of the reference rasterizer
  bool drop_near_clipped = false;
  bool drop_full_window = false;
};

// The samples of one kind under one reading, per view group.
struct GroupSamples {
  std::array<std::vector<double>, 4> metric_a, metric_b;  // TEu-norm, TEs-norm or LSEu, LSEs-norm
  std::array<uint64_t, 4> ideally_visible{}, total{};
};

geometry::Primitive make(const rundir::Experiment& e, geometry::Kind kind, uint64_t i, bool cube) {
  if (!cube) return geometry::make_primitive(e.seed, kind, i);
  geometry::Primitive p;
  p.kind = kind;
  p.index = i;
  util::CounterRng rng(e.seed, util::RngStream::kTriangle, i);
  for (int k = 0; k < geometry::vertex_count(kind); ++k)
    p.v[k] = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
  return p;
}

bool crosses_near_plane(const geometry::View& v, const geometry::Primitive& p) {
  for (int k = 0; k < geometry::vertex_count(p.kind); ++k) {
    const geometry::Vec4 c = v.to_clip(p.v[k]);
    if (c.z < -c.w) return true;
  }
  return false;
}

GroupSamples measure(const rundir::Experiment& e, geometry::Kind kind, const Reading& r,
                     const Options& o) {
  GroupSamples out;
  std::mutex mu;
  for (geometry::View view : e.views) {
    view.near = r.near;
    geometry::finish_view(view);
    const int g = view.group;
    if (g < 0 || g > 3) continue;
    constexpr size_t kChunks = 64;
    util::run_in_parallel(kChunks, o.jobs, [&](size_t chunk) {
      std::vector<double> a, b;
      uint64_t visible = 0, total = 0;
      for (uint64_t i = chunk; i < o.per_view; i += kChunks) {
        const geometry::Primitive p = make(e, kind, i, r.cube_vertices);
        ++total;
        if (kind == geometry::Kind::kTriangle) {
          const geometry::ClippedPolygon proj =
              geometry::clip_triangle(view, p.v[0], p.v[1], p.v[2]);
          if (!ideally_visible(proj)) continue;
          ++visible;
          const geometry::PixelSet lit =
              geometry::rasterize_polygon(proj, view.width, view.height, r.grid);
          if (lit.size() == 0) continue;  // false-invisible
          if (r.drop_near_clipped && crosses_near_plane(view, p)) continue;
          const metrics::TriangleMetrics m =
              metrics::measure_triangle(proj, lit, view.width, view.height);
          if (r.drop_full_window && m.full_window) continue;
          a.push_back(m.te_unsigned_norm);
          b.push_back(m.te_signed_norm);
        } else {
          const geometry::ClippedSegment seg = geometry::clip_segment(view, p.v[0], p.v[1]);
          if (!ideally_visible(seg)) continue;
          ++visible;
          const geometry::PixelSet lit =
              geometry::rasterize_segment(seg, view.width, view.height, r.grid);
          if (lit.size() == 0) continue;
          const metrics::LineMetrics m = metrics::measure_line(seg, lit, view.width, view.height);
          a.push_back(m.lse_unsigned_norm);
          b.push_back(m.lse_signed_norm);
        }
      }
      std::lock_guard<std::mutex> lock(mu);
      out.metric_a[g].insert(out.metric_a[g].end(), a.begin(), a.end());
      out.metric_b[g].insert(out.metric_b[g].end(), b.begin(), b.end());
      out.ideally_visible[g] += visible;
      out.total[g] += total;
    });
  }
  return out;
}

const analysis::PaperTableValues& paper_table(const analysis::PaperValues& paper,
                                              const std::string& number) {
  for (const auto& t : paper.tables)
    if (t.number == number) return t;
  throw util::UserError("the paper values have no Table " + number);
}

// "1.646 +- 0.010 (z +4.1 / +2.0)": value and SE at the paper's scale, z against Platform I and II
// with the paper's own sampling error (its 200,000 per group) added in quadrature.
std::string cell(double value, double se, double n, double paper_1, double paper_2, int decimals) {
  const double se_difference = se * std::sqrt(1 + n / kPaperPerGroup);
  auto z = [&](double paper) {
    if (std::isnan(paper)) return std::string("n/a");
    if (!(se_difference > 0)) return std::string(value == paper ? "0.0" : "SE 0");
    char buf[32];
    std::snprintf(buf, sizeof buf, "%+.1f", (value - paper) / se_difference);
    return std::string(buf);
  };
  char buf[160];
  std::snprintf(buf, sizeof buf, "%.*f +- %.*f (z %s / %s)", decimals, value, decimals, se,
                z(paper_1).c_str(), z(paper_2).c_str());
  return buf;
}

void print_metric_rows(const std::string& reading, const std::array<std::vector<double>, 4>& s,
                       const analysis::PaperTableValues& paper, const Options& o) {
  const double scale = std::pow(10.0, paper.scale_exponent);
  std::string median_row = "| " + reading + " | median |", iqr_row = "| " + reading + " | IQR |";
  for (int g = 0; g < 4; ++g) {
    std::vector<double> x = s[g];
    std::sort(x.begin(), x.end());
    if (x.empty()) {
      median_row += " |";
      iqr_row += " |";
      continue;
    }
    const stats::Description d = stats::describe(x);
    stats::BootstrapOptions bo;
    bo.resamples = o.bootstrap;
    const stats::MedianIqrBootstrap b = stats::bootstrap_median_iqr(x, bo);
    const int decimals = paper.scale_exponent == 6 ? 2 : 3;
    median_row += " " + cell(d.median * scale, b.median.se * scale, double(x.size()),
                             paper.median[0][g], paper.median[1][g], decimals) + " |";
    iqr_row += " " + cell(d.iqr * scale, b.iqr.se * scale, double(x.size()), paper.iqr[0][g],
                          paper.iqr[1][g], decimals) + " |";
  }
  std::printf("%s\n%s\n", median_row.c_str(), iqr_row.c_str());
}

void print_header(const std::string& title, const analysis::PaperTableValues& paper) {
  std::printf("\n### %s\n\n| reading | statistic |", title.c_str());
  for (int g = 0; g < 4; ++g)
    std::printf(" %c (FOV %g, %g px): ours +- SE (z I / II) |", 'A' + g, paper.fov_deg[g],
                paper.window[g]);
  std::printf("\n| --- | --- | ---: | ---: | ---: | ---: |\n");
  std::printf("| paper | median |");
  for (int g = 0; g < 4; ++g)
    std::printf(" I %g, II %g |", paper.median[0][g], paper.median[1][g]);
  std::printf("\n| paper | IQR |");
  for (int g = 0; g < 4; ++g) std::printf(" I %g, II %g |", paper.iqr[0][g], paper.iqr[1][g]);
  std::printf("\n");
}

// Share of ideally visible primitives against the paper's, z of the difference of two binomial
// proportions (ours over `total`, the paper's over 200,000).
std::string share_cell(uint64_t visible, uint64_t total, double paper_visible) {
  const double p = double(visible) / double(total), q = paper_visible / kPaperPerGroup;
  const double se = std::sqrt(p * (1 - p) / double(total) + q * (1 - q) / kPaperPerGroup);
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.3f%% (paper %.3f%%, z %+.1f)", 100 * p, 100 * q,
                (p - q) / se);
  return buf;
}

void print_visibility(const std::string& reading, const GroupSamples& s,
                      const std::array<double, 4>& paper) {
  std::printf("| %s |", reading.c_str());
  for (int g = 0; g < 4; ++g)
    std::printf(" %s |", share_cell(s.ideally_visible[g], s.total[g], paper[g]).c_str());
  std::printf("\n");
}

// Points within `margin` px outside the window, per view group, scaled to the paper's 200,000.
void print_point_margins(const rundir::Experiment& e, const Options& o) {
  std::printf(
      "\n### Points: false-invisible when points within m px outside the window lie in the field "
      "of view (per 200,000 points of a view group; paper, Platform I: 72, 154, 11, 29)\n\n"
      "| m (px) | A | B | C | D |\n| ---: | ---: | ---: | ---: | ---: |\n");
  for (double margin : {0.0, 0.25, 0.5, 1.0}) {
    std::array<uint64_t, 4> within{}, total{};
    std::mutex mu;
    for (const geometry::View& view : e.views) {
      const int g = view.group;
      if (g < 0 || g > 3) continue;
      util::run_in_parallel(64, o.jobs, [&](size_t chunk) {
        uint64_t n = 0, t = 0;
        for (uint64_t i = chunk; i < o.per_view; i += 64) {
          const geometry::Vec3 p = geometry::make_primitive(e.seed, geometry::Kind::kPoint, i).v[0];
          ++t;
          n += !metrics::project_point(view, p).visible &&
               metrics::inside_window_margin(view, p, margin);
        }
        std::lock_guard<std::mutex> lock(mu);
        within[g] += n;
        total[g] += t;
      });
    }
    std::printf("| %g |", margin);
    for (int g = 0; g < 4; ++g) {
      // A Poisson count: its 95% interval by the square-root rule, scaled with it.
      const double scale = kPaperPerGroup / double(total[g]), n = double(within[g]);
      std::printf(" %.0f (%.0f-%.0f) |", n * scale,
                  std::pow(std::max(0.0, std::sqrt(n) - 0.98), 2) * scale,
                  std::pow(std::sqrt(n + 1) + 0.98, 2) * scale);
    }
    std::printf("\n");
  }
}

int run(const Options& o) {
  const rundir::Experiment e = rundir::load_experiment(o.experiment);
  const analysis::PaperValues paper = analysis::load_paper_values(o.paper);
  std::printf("## Readings of the paper's method on the reference rasterizer\n\n%s, %llu "
              "primitives of each kind per view, bootstrap %d resamples; z against the paper's "
              "Platform I / II with the paper's own sampling error added.\n",
              o.experiment.c_str(), static_cast<unsigned long long>(o.per_view), o.bootstrap);
  const std::vector<Reading> near_readings = {
      {"near 0.01 (the text)", 0.01, false, {}}, {"near 1e-3", 1e-3, false, {}},
      {"near 1e-4", 1e-4, false, {}}, {"near 1e-5", 1e-5, false, {}}};
  std::vector<Reading> triangle_readings = near_readings;
  Reading r = near_readings[0];
  r.name = "near 0.01, near-clipped left out";
  r.drop_near_clipped = true;
  triangle_readings.push_back(r);
  r = near_readings[0];
  r.name = "near 0.01, full-window left out";
  r.drop_full_window = true;
  triangle_readings.push_back(r);
  r = near_readings[0];
  r.name = "near 0.01, vertices in the cube";
  r.cube_vertices = true;
  triangle_readings.push_back(r);
  r = near_readings[0];
  r.name = "near 0.01, 4 subpixel bits";
  r.grid = geometry::SubpixelGrid(4);
  triangle_readings.push_back(r);
  r.name = "near 0.01, 8 subpixel bits (llvmpipe's grid)";
  r.grid = geometry::SubpixelGrid(8);
  triangle_readings.push_back(r);
  std::vector<Reading> line_readings = near_readings;
  line_readings.push_back(r);

  std::vector<GroupSamples> triangles, lines;
  for (const Reading& reading : triangle_readings)
    triangles.push_back(measure(e, geometry::Kind::kTriangle, reading, o));
  for (const Reading& reading : line_readings)
    lines.push_back(measure(e, geometry::Kind::kLine, reading, o));

  print_header("Table 10, TEu-norm x10^3", paper_table(paper, "10"));
  for (size_t i = 0; i < triangles.size(); ++i)
    print_metric_rows(triangle_readings[i].name, triangles[i].metric_a, paper_table(paper, "10"), o);
  print_header("Table 9, TEs-norm x10^6", paper_table(paper, "9"));
  for (size_t i = 0; i < triangles.size(); ++i)
    print_metric_rows(triangle_readings[i].name, triangles[i].metric_b, paper_table(paper, "9"), o);
  print_header("Table 7, LSEu-norm x10^3", paper_table(paper, "7"));
  for (size_t i = 0; i < lines.size(); ++i)
    print_metric_rows(line_readings[i].name, lines[i].metric_a, paper_table(paper, "7"), o);
  print_header("Table 6, LSEs-norm x10^6", paper_table(paper, "6"));
  for (size_t i = 0; i < lines.size(); ++i)
    print_metric_rows(line_readings[i].name, lines[i].metric_b, paper_table(paper, "6"), o);

  std::printf("\n### Ideally visible (true-visible + false-invisible) share of each view group\n\n"
              "| reading | A | B | C | D |\n| --- | ---: | ---: | ---: | ---: |\n");
  for (size_t i = 0; i < near_readings.size(); ++i)
    print_visibility("triangles, " + near_readings[i].name, triangles[i], kPaperTriangleVisible);
  print_visibility("triangles, " + triangle_readings[6].name, triangles[6], kPaperTriangleVisible);
  for (size_t i = 0; i < near_readings.size(); ++i)
    print_visibility("lines, " + near_readings[i].name, lines[i], kPaperLineVisible);

  print_point_margins(e, o);
  return 0;
}

}  // namespace
}  // namespace ra

int main(int argc, char** argv) {
  CLI::App app{"The NIST paper's numbers under candidate readings of its method (reference "
               "rasterizer)"};
  ra::Options o;
  app.add_option("--experiment", o.experiment, "views and seed (default experiments/nist2008.toml)");
  app.add_option("--paper", o.paper, "the paper's values (default experiments/papers/...)");
  app.add_option("--per-view", o.per_view, "primitives of each kind per view (default 100000)")
      ->check(CLI::Range(uint64_t(100), uint64_t(10000000)));
  app.add_option("--bootstrap", o.bootstrap, "bootstrap resamples (default 500)")
      ->check(CLI::Range(2, 100000));
  app.add_option("--jobs", o.jobs, "threads (default: the number of cores)");
  CLI11_PARSE(app, argc, argv);
  try {
    return ra::run(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "paper_readings: %s\n", e.what());
    return 2;
  }
}
