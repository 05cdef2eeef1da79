// Table 6 and c over repeated runs of the study (repeated_runs.h).
#include "timing/repeated_runs.h"

#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

#include "stats/descriptive.h"

namespace ra::timing {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

RunSpread spread_over_runs(const std::vector<double>& values, double confidence) {
  if (!(confidence > 0 && confidence < 1))
    throw std::invalid_argument("spread_over_runs: confidence must be in (0, 1)");
  RunSpread s;
  s.values = values;
  s.confidence = confidence;
  std::vector<double> finite;
  for (double v : values)
    if (std::isfinite(v)) finite.push_back(v);
  s.n = finite.size();
  s.mean = s.sd = s.min = s.max = s.ci_low = s.ci_high = kNaN;
  if (finite.empty()) return s;
  const stats::MeanVariance mv = stats::mean_and_variance(finite);
  s.mean = mv.mean;
  s.min = *std::min_element(finite.begin(), finite.end());
  s.max = *std::max_element(finite.begin(), finite.end());
  if (s.n < 2) return s;  // no spread can be estimated from one run
  s.sd = mv.sd;
  const boost::math::students_t dist(double(s.n - 1));
  const double t = boost::math::quantile(boost::math::complement(dist, (1 - confidence) / 2));
  const double half = t * s.sd / std::sqrt(double(s.n));
  s.ci_low = s.mean - half;
  s.ci_high = s.mean + half;
  return s;
}

std::vector<std::string> rank_methods(const std::map<std::string, double>& errors,
                                      const std::vector<std::string>& methods) {
  auto error_of = [&](const std::string& m) {
    const auto it = errors.find(m);
    return it == errors.end() || !std::isfinite(it->second) ? kNaN : it->second;
  };
  std::vector<std::string> ranked = methods;
  std::stable_sort(ranked.begin(), ranked.end(), [&](const std::string& a, const std::string& b) {
    const double ea = error_of(a), eb = error_of(b);
    if (std::isnan(eb)) return !std::isnan(ea);  // finite before missing
    return !std::isnan(ea) && ea < eb;
  });
  return ranked;
}

bool is_paper_method(const std::string& method) {
  return method == "h1" || method == "h2" || method == "h3" || method == "h4" || method == "pos";
}

RepeatedPlatform aggregate_runs(const std::string& platform, const std::vector<std::string>& methods,
                                const std::vector<RunOutcome>& runs, double confidence) {
  RepeatedPlatform p;
  p.platform = platform;
  p.methods = methods;
  std::set<std::string> scenes;
  std::vector<double> c;
  for (const RunOutcome& r : runs) {
    p.wall_s.push_back(r.wall_s);
    if (!r.ok) {
      ++p.failed;
      continue;
    }
    ++p.runs;
    c.push_back(r.c_us);
    for (const auto& [scene, row] : r.table6_ms2) scenes.insert(scene);
  }
  p.c_us = spread_over_runs(c, confidence);

  std::vector<std::string> paper;
  for (const std::string& m : methods)
    if (is_paper_method(m)) paper.push_back(m);
  for (const std::string& scene : scenes) {
    SceneRanking& rk = p.ranking[scene];
    for (const std::string& m : methods) rk.wins[m] = 0;
    for (const std::string& m : paper) rk.paper_wins[m] = 0;
    std::map<std::string, std::vector<double>> per_method;
    for (const RunOutcome& r : runs) {
      if (!r.ok) continue;
      const auto row_it = r.table6_ms2.find(scene);
      const std::map<std::string, double> row =
          row_it == r.table6_ms2.end() ? std::map<std::string, double>{} : row_it->second;
      for (const std::string& m : methods)
        per_method[m].push_back(row.count(m) ? row.at(m) : kNaN);
      rk.per_run.push_back(rank_methods(row, methods));
      // a winner needs a finite error: rank_methods puts the missing ones last
      const std::string best = rk.per_run.back().empty() ? "" : rk.per_run.back().front();
      if (best.empty() || !row.count(best) || !std::isfinite(row.at(best))) {
        ++rk.runs_without_winner;
        continue;
      }
      ++rk.wins[best];
      const std::vector<std::string> paper_ranked = rank_methods(row, paper);
      if (!paper_ranked.empty() && row.count(paper_ranked.front()) &&
          std::isfinite(row.at(paper_ranked.front())))
        ++rk.paper_wins[paper_ranked.front()];
    }
    for (const std::string& m : methods)
      p.table6_ms2[scene][m] = spread_over_runs(per_method[m], confidence);
  }
  return p;
}

}  // namespace ra::timing
