// Heuristics H1-H4, the system constant c, the per-object sampling table and Table 6's error
// (Wimmer & Wonka 2003, sections 4.2, 5.2, 5.3, 7.2). See time_heuristics.h for the methods.
#include "timing/time_heuristics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "stats/descriptive.h"
#include "stats/linear_regression.h"
#include "util/errors.h"

namespace ra::timing {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kTwoPi = 6.283185307179586;

struct Columns {
  std::vector<std::vector<double>> x;
  std::vector<std::string> names, units;
};

// The predictor columns of the linear heuristics (H1, H2, H4) and of H3's two branches.
Columns columns(const std::vector<ObjectCounts>& x, Heuristic h, int branch = 0) {
  Columns c;
  auto add = [&](double ObjectCounts::*field, const char* name, const char* unit) {
    std::vector<double> col;
    col.reserve(x.size());
    for (const ObjectCounts& o : x) col.push_back(o.*field);
    c.x.push_back(std::move(col));
    c.names.push_back(name);
    c.units.push_back(unit);
  };
  switch (h) {
    case Heuristic::kH1: add(&ObjectCounts::triangles, "c", "us/triangle"); break;
    case Heuristic::kH2: add(&ObjectCounts::transformed, "c", "us/vertex"); break;
    case Heuristic::kH4:
      add(&ObjectCounts::transformed, "c1", "us/vertex");
      add(&ObjectCounts::pixels, "c2", "us/pixel");
      break;
    case Heuristic::kH3:
      if (branch == 0) {
        add(&ObjectCounts::triangles, "c1", "us/triangle");
        add(&ObjectCounts::vertices, "c2", "us/vertex");
      } else {
        add(&ObjectCounts::pixels, "c3", "us/pixel");
      }
      break;
  }
  return c;
}

double centred_tss(const std::vector<double>& y) {
  double m = 0;
  for (double v : y) m += v;
  m /= double(y.size());
  double s = 0;
  for (double v : y) s += (v - m) * (v - m);
  return s;
}

void finish_quality(HeuristicFit& f, const std::vector<ObjectCounts>& x,
                    const std::vector<double>& y) {
  f.n = y.size();
  f.sse = 0;
  for (std::size_t i = 0; i < y.size(); ++i) {
    const double r = y[i] - f.predict(x[i]);
    f.sse += r * r;
  }
  f.rmse = std::sqrt(f.sse / double(f.n));
  const double tss = centred_tss(y);
  f.r_squared = tss > 0 ? 1 - f.sse / tss : kNaN;
}

// One branch of H3: [b, c...] (intercept) or [c...], evaluated on one sample.
struct Branch {
  std::vector<double> coef, se;
  double eval(const std::vector<std::vector<double>>& cols, std::size_t i, bool intercept) const {
    double v = intercept ? coef[0] : 0.0;
    for (std::size_t j = 0; j < cols.size(); ++j) v += coef[j + intercept] * cols[j][i];
    return v;
  }
};

// Least squares of a branch on the samples in `rows`; false when it cannot be fitted (too few
// samples, degenerate design): the caller keeps the previous coefficients.
bool fit_branch(const std::vector<std::vector<double>>& cols, const std::vector<double>& y,
                const std::vector<std::size_t>& rows, bool intercept, Branch& out) {
  const std::size_t p = cols.size() + intercept;
  if (rows.size() < p + 1) return false;
  std::vector<std::vector<double>> sub(cols.size());
  std::vector<double> ys;
  ys.reserve(rows.size());
  for (std::size_t i : rows) {
    ys.push_back(y[i]);
    for (std::size_t j = 0; j < cols.size(); ++j) sub[j].push_back(cols[j][i]);
  }
  try {
    const stats::LinearFit f = stats::fit_least_squares(sub, ys, intercept);
    out.coef = f.coefficients;
    out.se = f.standard_deviations;
    return true;
  } catch (const util::UserError&) {
    return false;
  }
}

}  // namespace

const char* heuristic_name(Heuristic h) {
  switch (h) {
    case Heuristic::kH1: return "h1";
    case Heuristic::kH2: return "h2";
    case Heuristic::kH3: return "h3";
    case Heuristic::kH4: return "h4";
  }
  return "?";
}

const char* heuristic_formula(Heuristic h) {
  switch (h) {
    case Heuristic::kH1: return "c*tris";
    case Heuristic::kH2: return "c*tv";
    case Heuristic::kH3: return "max(c1*tris + c2*v, c3*pix)";
    case Heuristic::kH4: return "c1*tv + c2*pix";
  }
  return "?";
}

ObjectCounts counts_of(const ObjectSample& s) {
  return {double(s.triangles), double(s.vertices), double(s.transformed), double(s.pixels)};
}

double HeuristicFit::predict(const ObjectCounts& x) const {
  const double* c = coefficients.data();
  const double b = intercept ? c[0] : 0.0;
  const int o = intercept ? 1 : 0;
  switch (heuristic) {
    case Heuristic::kH1: return b + c[o] * x.triangles;
    case Heuristic::kH2: return b + c[o] * x.transformed;
    case Heuristic::kH4: return b + c[o] * x.transformed + c[o + 1] * x.pixels;
    case Heuristic::kH3: {
      const double g = b + c[o] * x.triangles + c[o + 1] * x.vertices;
      const double r = (intercept ? c[3] : 0.0) + c[o + (intercept ? 3 : 2)] * x.pixels;
      return std::max(g, r);
    }
  }
  return kNaN;
}

HeuristicFit fit_heuristic(Heuristic h, const std::vector<ObjectCounts>& x,
                           const std::vector<double>& y_us, bool intercept) {
  if (x.size() != y_us.size())
    throw std::invalid_argument("fit_heuristic: counts and times differ in length");
  if (h == Heuristic::kH3) return fit_h3(x, y_us, intercept);
  const Columns c = columns(x, h);
  const std::size_t p = c.x.size() + intercept;
  if (y_us.size() < p + 2)
    throw util::UserError(std::string("cannot fit ") + heuristic_name(h) + ": " +
                          std::to_string(y_us.size()) + " object measurement(s), at least " +
                          std::to_string(p + 2) + " needed");
  const stats::LinearFit f = stats::fit_least_squares(c.x, y_us, intercept, c.names);
  HeuristicFit out;
  out.heuristic = h;
  out.intercept = intercept;
  if (intercept) out.names.push_back("b0"), out.units.push_back("us");
  out.names.insert(out.names.end(), c.names.begin(), c.names.end());
  out.units.insert(out.units.end(), c.units.begin(), c.units.end());
  out.coefficients = f.coefficients;
  out.standard_errors = f.standard_deviations;
  finish_quality(out, x, y_us);
  return out;
}

HeuristicFit fit_h3(const std::vector<ObjectCounts>& x, const std::vector<double>& y,
                    bool intercept, int max_iterations) {
  if (x.size() != y.size()) throw std::invalid_argument("fit_h3: counts and times differ in length");
  const std::size_t n = y.size();
  const Columns g = columns(x, Heuristic::kH3, 0), r = columns(x, Heuristic::kH3, 1);
  const std::size_t pg = g.x.size() + intercept, pr = r.x.size() + intercept;
  if (n < pg + pr + 2)
    throw util::UserError("cannot fit h3: " + std::to_string(n) +
                          " object measurement(s), at least " + std::to_string(pg + pr + 2) +
                          " needed");

  auto sse_of = [&](const Branch& bg, const Branch& br) {
    double s = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double e = y[i] - std::max(bg.eval(g.x, i, intercept), br.eval(r.x, i, intercept));
      s += e * e;
    }
    return s;
  };

  struct Best {
    double sse = std::numeric_limits<double>::infinity();
    Branch bg, br;
    int iterations = 0;
    std::string start;
    bool converged = false;
    std::vector<char> geometry;  // per sample: assigned to the geometry branch
  } best;

  std::vector<std::size_t> all(n);
  for (std::size_t i = 0; i < n; ++i) all[i] = i;

  auto run = [&](Branch bg, Branch br, const std::string& name) {
    std::vector<char> assign(n, 2);  // 2: not yet assigned
    for (int it = 1; it <= max_iterations; ++it) {
      std::vector<char> next(n);
      std::vector<std::size_t> gi, ri;
      for (std::size_t i = 0; i < n; ++i) {
        next[i] = bg.eval(g.x, i, intercept) >= br.eval(r.x, i, intercept);
        (next[i] ? gi : ri).push_back(i);
      }
      const bool stable = next == assign;
      const double s = sse_of(bg, br);
      if (s < best.sse) best = {s, bg, br, it, name, stable, next};
      if (stable) return;
      assign = next;
      fit_branch(g.x, y, gi, intercept, bg);
      fit_branch(r.x, y, ri, intercept, br);
    }
  };

  // (a) the two separate fits on all samples
  Branch bg0, br0;
  if (!fit_branch(g.x, y, all, intercept, bg0) || !fit_branch(r.x, y, all, intercept, br0))
    throw util::UserError(
        "cannot fit h3: the design is degenerate (e.g. all #pix or all #tris equal)");
  run(bg0, br0, "separate fits");
  // (b) splits by #pix / #tris
  std::vector<double> ratio(n);
  for (std::size_t i = 0; i < n; ++i) ratio[i] = x[i].pixels / std::max(1.0, x[i].triangles);
  std::vector<double> sorted = ratio;
  std::sort(sorted.begin(), sorted.end());
  for (double q : {0.25, 0.5, 0.75}) {
    const double cut = stats::quantile_sorted(sorted, q);
    std::vector<std::size_t> gi, ri;
    for (std::size_t i = 0; i < n; ++i) (ratio[i] > cut ? ri : gi).push_back(i);
    Branch bg = bg0, br = br0;
    fit_branch(g.x, y, gi, intercept, bg);
    fit_branch(r.x, y, ri, intercept, br);
    run(bg, br, "split at the " + std::to_string(int(q * 100)) + " % quantile of pix/tris");
  }
  // (c) all geometry-limited: raster branch zero
  {
    Branch br;
    br.coef.assign(pr, 0.0);
    br.se.assign(pr, 0.0);
    run(bg0, br, "all geometry-limited");
  }

  // Standard errors of the winner: each branch refitted on its final assignment.
  std::vector<std::size_t> gi, ri;
  for (std::size_t i = 0; i < n; ++i) (best.geometry[i] ? gi : ri).push_back(i);
  Branch bg = best.bg, br = best.br, refit;
  bg.se = fit_branch(g.x, y, gi, intercept, refit) ? refit.se : std::vector<double>(pg, kNaN);
  br.se = fit_branch(r.x, y, ri, intercept, refit) ? refit.se : std::vector<double>(pr, kNaN);

  HeuristicFit out;
  out.heuristic = Heuristic::kH3;
  out.intercept = intercept;
  if (intercept) out.names.push_back("bg"), out.units.push_back("us");
  out.names.insert(out.names.end(), g.names.begin(), g.names.end());
  out.units.insert(out.units.end(), g.units.begin(), g.units.end());
  if (intercept) out.names.push_back("br"), out.units.push_back("us");
  out.names.insert(out.names.end(), r.names.begin(), r.names.end());
  out.units.insert(out.units.end(), r.units.begin(), r.units.end());
  out.coefficients = bg.coef;
  out.coefficients.insert(out.coefficients.end(), br.coef.begin(), br.coef.end());
  out.standard_errors = bg.se;
  out.standard_errors.insert(out.standard_errors.end(), br.se.begin(), br.se.end());
  out.geometry_limited = gi.size();
  out.raster_limited = ri.size();
  out.iterations = best.iterations;
  out.start = best.start;
  out.converged = best.converged;
  finish_quality(out, x, y);
  return out;
}

// ---- system tasks ----

SystemTaskStats system_task_stats(const std::vector<double>& frame_us, double confidence) {
  if (frame_us.empty()) throw std::invalid_argument("system_task_stats: no frame times");
  if (!(confidence > 0 && confidence < 1))
    throw std::invalid_argument("system_task_stats: confidence must be in (0, 1)");
  std::vector<double> s = frame_us;
  std::sort(s.begin(), s.end());
  const stats::Description d = stats::describe(s);
  SystemTaskStats out;
  out.n = s.size();
  out.min_us = d.min;
  out.max_us = d.max;
  out.median_us = d.median;
  out.mean_us = d.mean;
  out.sd_us = d.sd;
  out.confidence = confidence;
  out.q99_us = stats::quantile_sorted(s, confidence);
  out.c_us = out.q99_us - out.min_us;
  return out;
}

// ---- pos ----

double PosGrid::alpha_at(int i) const {
  return n_alpha == 1 ? alpha_min : alpha_min + (alpha_max - alpha_min) * i / (n_alpha - 1);
}
double PosGrid::gamma_at(int k) const { return kTwoPi * k / n_gamma; }
double PosGrid::phi_at(int j) const {
  return n_phi == 1 ? phi_min : phi_min + (phi_max - phi_min) * j / (n_phi - 1);
}

PosTable::PosTable(const PosGrid& grid, double prune_alpha)
    : grid_(grid), prune_alpha_(prune_alpha), values_(grid.cells(), kNaN) {
  if (grid.n_alpha < 1 || grid.n_gamma < 1 || grid.n_phi < 1 || !(grid.alpha_min > 0) ||
      !(grid.alpha_max >= grid.alpha_min) || !(grid.phi_max >= grid.phi_min))
    throw std::invalid_argument("PosTable: invalid grid");
}

std::size_t PosTable::index(int i, int k, int j) const {
  if (i < 0 || i >= grid_.n_alpha || k < 0 || k >= grid_.n_gamma || j < 0 || j >= grid_.n_phi)
    throw std::out_of_range("PosTable: grid index out of range");
  return (std::size_t(i) * grid_.n_gamma + k) * grid_.n_phi + j;
}

std::vector<std::array<int, 3>> PosTable::points_to_measure() const {
  std::vector<std::array<int, 3>> out;
  for (int i = 0; i < grid_.n_alpha; ++i) {
    if (pruned_row(i)) {
      out.push_back({i, 0, 0});
      continue;
    }
    for (int k = 0; k < grid_.n_gamma; ++k)
      for (int j = 0; j < grid_.n_phi; ++j) out.push_back({i, k, j});
  }
  return out;
}

void PosTable::set(int i, int k, int j, double us) {
  if (pruned_row(i)) {
    for (int kk = 0; kk < grid_.n_gamma; ++kk)
      for (int jj = 0; jj < grid_.n_phi; ++jj) values_[index(i, kk, jj)] = us;
  } else {
    values_[index(i, k, j)] = us;
  }
}

double PosTable::at(int i, int k, int j) const { return values_[index(i, k, j)]; }

bool PosTable::complete() const {
  return !values_.empty() &&
         std::none_of(values_.begin(), values_.end(), [](double v) { return std::isnan(v); });
}

double PosTable::lookup(double alpha, double gamma, double phi, PosLookup how) const {
  if (values_.empty()) throw std::logic_error("PosTable::lookup on an empty table");
  // continuous grid coordinates
  auto coord = [](double v, double lo, double hi, int n) {
    if (n == 1 || hi <= lo) return 0.0;
    return std::clamp((v - lo) / (hi - lo), 0.0, 1.0) * (n - 1);
  };
  const double u = coord(alpha, grid_.alpha_min, grid_.alpha_max, grid_.n_alpha);
  const double w = coord(phi, grid_.phi_min, grid_.phi_max, grid_.n_phi);
  double g = std::fmod(gamma, kTwoPi);
  if (g < 0) g += kTwoPi;
  const double v = g / kTwoPi * grid_.n_gamma;  // in [0, n_gamma)
  if (how == PosLookup::kNearest) {
    const int i = int(std::lround(u)), j = int(std::lround(w));
    const int k = int(std::lround(v)) % grid_.n_gamma;
    return at(i, k, j);
  }
  const int i0 = std::min(int(u), grid_.n_alpha - 1), j0 = std::min(int(w), grid_.n_phi - 1);
  const int k0 = std::min(int(v), grid_.n_gamma - 1);
  const int i1 = std::min(i0 + 1, grid_.n_alpha - 1), j1 = std::min(j0 + 1, grid_.n_phi - 1);
  const int k1 = (k0 + 1) % grid_.n_gamma;
  const double fu = u - i0, fw = w - j0, fv = v - k0;
  double s = 0;
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      for (int c = 0; c < 2; ++c) {
        const double weight = (a ? fu : 1 - fu) * (b ? fv : 1 - fv) * (c ? fw : 1 - fw);
        if (weight == 0) continue;
        s += weight * at(a ? i1 : i0, b ? k1 : k0, c ? j1 : j0);
      }
  return s;
}

// ---- Table 6 ----

double average_squared_error_ms2(const std::vector<double>& predicted_us,
                                 const std::vector<double>& measured_us) {
  if (predicted_us.empty() || predicted_us.size() != measured_us.size())
    throw std::invalid_argument("average_squared_error_ms2: empty or different lengths");
  double s = 0;
  for (std::size_t i = 0; i < predicted_us.size(); ++i) {
    const double e = (predicted_us[i] - measured_us[i]) / 1000.0;
    s += e * e;
  }
  return s / double(predicted_us.size());
}

}  // namespace ra::timing
