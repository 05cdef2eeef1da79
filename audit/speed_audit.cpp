#include "audit/speed_audit.h"

#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "audit/distribution_audit.h"
#include "stats/descriptive.h"
#include "stats/signed_rank.h"

namespace ra::audit {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kMaxRepeatsToSettle = 200;

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
      // Past the cap the estimate sits on the band's edge: no practical number of repeats.
      d.repeats_to_settle = r <= kMaxRepeatsToSettle ? int(r) : 0;
    }
  }
  return d;
}

RoundInterval round_interval(const std::vector<double>& d) {
  RoundInterval out{kNaN, kNaN, kNaN};
  if (d.empty()) return out;
  const stats::MeanVariance mv = stats::mean_and_variance(d);
  out.ratio = std::exp(mv.mean);
  if (d.size() < 2) return out;
  const boost::math::students_t t(double(d.size() - 1));
  const double half =
      boost::math::quantile(boost::math::complement(t, 0.025)) * std::sqrt(mv.variance / double(d.size()));
  out.low = std::exp(mv.mean - half);
  out.high = std::exp(mv.mean + half);
  return out;
}

std::string speed_ratio_text(double ratio, double low, double high) {
  if (!std::isfinite(ratio)) return "-";
  char text[96];
  std::snprintf(text, sizeof text, "%.3fx [%.3f, %.3f]", ratio, low, high);
  return text;
}

std::vector<double> round_log_ratios(const RoundTimes& over, const RoundTimes& under) {
  std::vector<double> out;
  const std::size_t rounds = over.empty() ? 0 : over[0].size();
  std::vector<double> d(over.size());
  for (std::size_t r = 0; r < rounds; ++r) {
    for (std::size_t i = 0; i < d.size(); ++i) d[i] = std::log(over[i][r] / under[i][r]);
    out.push_back(stats::hodges_lehmann(d));
  }
  return out;
}

namespace {

std::vector<double> per_primitive_medians(const RoundTimes& t) {
  std::vector<double> out;
  for (const std::vector<double>& rounds : t) out.push_back(stats::median(rounds));
  return out;
}

}  // namespace

SpeedComparison compare_speed(const RoundTimes& baseline_us, const RoundTimes& current_us,
                              const RoundTimes& control_us, double threshold) {
  const std::size_t n = baseline_us.size();
  const std::size_t rounds = n ? baseline_us[0].size() : 0;
  auto shaped = [&](const RoundTimes& t) {
    if (t.size() != n) return false;
    for (const std::vector<double>& r : t)
      if (r.size() != rounds) return false;
    return true;
  };
  if (!shaped(baseline_us) || !shaped(current_us) || (!control_us.empty() && !shaped(control_us)))
    throw std::invalid_argument("compare_speed: the sides' samples differ in shape");
  SpeedComparison c;
  c.n = n;
  c.repeats = int(rounds);
  c.ratio = c.low = c.high = kNaN;
  c.control_ratio = c.control_low = c.control_high = kNaN;
  c.band = std::exp(std::log1p(threshold));  // without a control; widened by it below
  if (n == 0 || rounds == 0) {
    c.reason = "no primitive timed on every side";
    return c;
  }
  const std::vector<double> base = per_primitive_medians(baseline_us),
                            cur = per_primitive_medians(current_us);
  c.baseline_median_us = stats::median(base);
  c.current_median_us = stats::median(cur);
  const std::vector<double> d = round_log_ratios(current_us, baseline_us);
  const std::vector<double> a =
      control_us.empty() ? std::vector<double>{} : round_log_ratios(control_us, baseline_us);
  const RoundInterval ratio = round_interval(d);
  c.ratio = ratio.ratio, c.low = ratio.low, c.high = ratio.high;
  double control_bound = 0;
  if (!a.empty()) {
    const RoundInterval control = round_interval(a);
    c.control_ratio = control.ratio, c.control_low = control.low, c.control_high = control.high;
    control_bound = std::fabs(std::log(control.ratio));
  }
  c.band = std::exp(std::max(std::log1p(threshold), control_bound));
  if (rounds < 2) {
    c.reason = "one round: an interval needs at least 2 (--speed-repeats)";
  } else {
    const SpeedDecision decision = decide_speed(c.low, c.high, threshold, control_bound, int(rounds));
    c.verdict = decision.verdict;
    c.repeats_to_settle = decision.repeats_to_settle;
  }
  // The mission's tests beside the interval: one Box-Cox lambda for both samples.
  const analysis::SampleComparison s = analysis::compare_samples({base, cur});
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
