#include "audit/speed_audit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "audit/distribution_audit.h"
#include "stats/descriptive.h"
#include "stats/signed_rank.h"

namespace ra::audit {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kMaxRepeatsToSettle = 1000;

std::vector<double> log_ratios(const std::vector<double>& over, const std::vector<double>& under) {
  std::vector<double> d(over.size());
  for (std::size_t i = 0; i < d.size(); ++i) d[i] = std::log(over[i] / under[i]);
  return d;
}

}  // namespace

const char* speed_verdict_name(SpeedVerdict v) {
  switch (v) {
    case SpeedVerdict::kSame: return "same";
    case SpeedVerdict::kFaster: return "faster";
    case SpeedVerdict::kSlower: return "slower";
    case SpeedVerdict::kUnknown: return "unknown";
  }
  return "unknown";
}

SpeedDecision decide_speed(double low, double high, double threshold, double control_bound,
                           int repeats) {
  SpeedDecision d;
  if (!(low > 0 && high >= low && std::isfinite(high))) return d;
  // The band's edge belongs to it, whatever the last bit of log(1 + threshold) is.
  const double b = std::max(std::log1p(threshold), control_bound) + 1e-12;
  const double lo = std::log(low), hi = std::log(high);
  if (lo > b) {
    d.verdict = SpeedVerdict::kSlower;
  } else if (hi < -b) {
    d.verdict = SpeedVerdict::kFaster;
  } else if (lo >= -b && hi <= b) {
    d.verdict = SpeedVerdict::kSame;
  } else {
    // The interval straddles an edge of the band: it must shrink to the distance between its
    // centre and the nearer edge (outside the band: to lie beyond it; inside: within it).
    const double centre = (lo + hi) / 2, half = (hi - lo) / 2;
    const double room = std::fabs(std::fabs(centre) - b);
    if (room > 0 && half > 0) {
      const double r = std::ceil(std::max(1, repeats) * (half / room) * (half / room));
      d.repeats_to_settle = int(std::min<double>(r, kMaxRepeatsToSettle));
    }
  }
  return d;
}

SpeedComparison compare_speed(const std::vector<double>& baseline_us,
                              const std::vector<double>& current_us,
                              const std::vector<double>& control_us, double threshold,
                              int repeats) {
  if (current_us.size() != baseline_us.size() ||
      (!control_us.empty() && control_us.size() != baseline_us.size()))
    throw std::invalid_argument("compare_speed: the sides' samples differ in size");
  SpeedComparison c;
  c.n = baseline_us.size();
  c.repeats = repeats;
  c.ratio = c.low = c.high = kNaN;
  c.control_ratio = c.control_low = c.control_high = kNaN;
  c.baseline_median_us = stats::median_or_nan(baseline_us);
  c.current_median_us = stats::median_or_nan(current_us);
  c.band = std::exp(std::log1p(threshold));  // without a control; widened by it below
  stats::SignedRankInterval ci;
  try {
    ci = stats::signed_rank_interval(log_ratios(current_us, baseline_us));
  } catch (const std::invalid_argument&) {
    c.reason = std::to_string(c.n) + " primitive(s) timed on every side: at least 6 are needed";
    return c;
  }
  c.ratio = std::exp(ci.estimate), c.low = std::exp(ci.low), c.high = std::exp(ci.high);
  double control_bound = 0;
  if (!control_us.empty()) {
    const stats::SignedRankInterval a = stats::signed_rank_interval(log_ratios(control_us, baseline_us));
    c.control_ratio = std::exp(a.estimate), c.control_low = std::exp(a.low),
    c.control_high = std::exp(a.high);
    control_bound = std::max(std::fabs(a.low), std::fabs(a.high));
  }
  c.band = std::exp(std::max(std::log1p(threshold), control_bound));
  const SpeedDecision d = decide_speed(c.low, c.high, threshold, control_bound, repeats);
  c.verdict = d.verdict;
  c.repeats_to_settle = d.repeats_to_settle;
  // The mission's tests beside the interval: one Box-Cox lambda for both samples.
  const analysis::SampleComparison s = analysis::compare_samples({baseline_us, current_us});
  c.box_cox = s.box_cox;
  c.welch = s.transformed.welch;
  c.levene = s.transformed.levene_median;
  return c;
}

void adjust_speed_tests(std::vector<SpeedComparison>& comparisons) {
  std::vector<double> p;
  std::vector<double*> where;
  for (SpeedComparison& c : comparisons)
    for (auto [outcome, adjusted] : {std::pair{&c.welch, &c.welch_p_holm},
                                     std::pair{&c.levene, &c.levene_p_holm}}) {
      *adjusted = 1;
      if (!outcome->defined) continue;
      p.push_back(outcome->p_value);
      where.push_back(adjusted);
    }
  const std::vector<double> adjusted = holm_adjust(p);
  for (std::size_t i = 0; i < adjusted.size(); ++i) *where[i] = adjusted[i];
}

std::size_t SpeedAudit::count(SpeedVerdict v) const {
  return std::size_t(std::count_if(comparisons.begin(), comparisons.end(),
                                   [&](const SpeedComparison& c) { return c.verdict == v; }));
}

}  // namespace ra::audit
