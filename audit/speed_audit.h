// The audit's verdict on drawing time: per platform pair, kind and view group, how much faster or
// slower the current side draws than the baseline, with a 95% interval, judged against a
// threshold and against an A/A control measured the same way at the same time.
//
// Measurement (audit/speed_timing.h): the first `per_view` primitives of every kind and view
// (primitive i is a pure function of seed, kind and i, so these are a random sample) are drawn
// alone by the baseline side, the current side and the control (the baseline drawn again), in
// `repeats` rounds of fresh processes that take turns (microseconds, render_us's clock).
//
// Statistics, per pair, kind and view group (n primitives with a time on every side in every
// round):
// - ratio: the unit of replication is the round, not the primitive. Every primitive of one
//   process shares that process's luck (what else the machine ran then, where its memory landed),
//   so primitives of one round are not independent evidence; rounds are. Per round r, d_r is the
//   Hodges-Lehmann estimate (stats/signed_rank.h) of the paired log ratios log(current / baseline)
//   of that round's processes (paired: one primitive can take 100 times another's time, and the
//   pairing removes that spread). The ratio is exp(mean of d_r), its 95% interval exp of Student's
//   t interval over the rounds (mean +- t(0.975, R - 1) sd / sqrt(R)): wide when the rounds
//   disagree, which is what a loaded machine does.
// - beside it, the mission's tests on the two samples of per-primitive times (each the median of
//   its rounds): Welch's t and Levene's (median centre) on Box-Cox transformed times, one lambda
//   for both samples chosen on the pooled data (analysis/view_equivalence.h), Holm-adjusted over
//   every speed test of the audit (a family of their own: the pixel distributions' family and
//   adjusted p-values stay what they are without timing);
// - the control's ratio and interval, the same way: what two identical sides show on this machine
//   now.
// Verdict (decide_speed): with b = max(log(1 + threshold), |log control ratio|), `slower` when the
// whole interval lies above exp(b), `faster` when it lies below exp(-b), `same` when it lies
// within [exp(-b), exp(b)], else `unknown`, with about how many repeats would settle it. The
// tests do not decide: a significant test with an interval inside the band is a change too small
// to matter.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "analysis/view_equivalence.h"
#include "audit/audit_compare.h"
#include "audit/flake_check.h"
#include "audit/run_identity.h"
#include "audit/speed_timing.h"
#include "geometry/primitive.h"

namespace ra::audit {

enum class SpeedVerdict { kSame, kFaster, kSlower, kUnknown };
const char* speed_verdict_name(SpeedVerdict v);  // "same", "faster", "slower", "unknown"

struct SpeedOptions {
  bool enabled = false;     // `audit --speed`
  int repeats = 10;         // rounds: fresh processes per side (>= 2 for an interval)
  uint64_t per_view = 100;  // primitives of each kind and view timed
  double threshold = 0.05;  // a change counts only when its whole interval lies beyond this
  bool warn_only = false;   // a slowdown is reported but does not make the verdict `changed`
  std::string program;      // runs `serve-shards`; empty: util/worker_program.h
};

struct SpeedDecision {
  SpeedVerdict verdict = SpeedVerdict::kUnknown;
  // kUnknown: about this many repeats in all would narrow the interval enough (assuming its width
  // shrinks as 1 / sqrt(repeats)); 0 when no practical number can (over 200: the estimate sits on
  // the band's edge).
  int repeats_to_settle = 0;
};

// The verdict of an interval [low, high] of a ratio (current / baseline, both > 0) against the band
// [1/exp(b), exp(b)], b = max(log(1 + threshold), control_bound) (control_bound: |log| of the A/A
// control's ratio, 0 without a control), measured with `repeats` repeats.
SpeedDecision decide_speed(double low, double high, double threshold, double control_bound,
                           int repeats);

// One comparison of drawing time.
struct SpeedComparison {
  std::size_t pair = 0;  // index into the audit's PlatformPair list
  std::string platform, baseline_platform;
  geometry::Kind kind = geometry::Kind::kPoint;
  int view_group = 0;   // 0 = A
  std::string group;    // "A", ...
  std::size_t n = 0;    // primitives timed on every side
  int repeats = 0;
  // medians over the primitives of their per-primitive medians, microseconds
  double baseline_median_us = 0, current_median_us = 0;
  // current / baseline: the Hodges-Lehmann ratio and its 95% interval (NaN when n is too small)
  double ratio = 0, low = 0, high = 0;
  // the control (the baseline drawn again) / baseline, the same way; NaN without a control
  double control_ratio = 0, control_low = 0, control_high = 0;
  double band = 0;  // exp(b): changes within [1/band, band] are not counted
  analysis::BoxCoxFit box_cox;           // one lambda for both samples
  analysis::TestOutcome welch, levene;   // on the Box-Cox transformed per-primitive times
  double welch_p_holm = 1, levene_p_holm = 1;
  SpeedVerdict verdict = SpeedVerdict::kUnknown;
  int repeats_to_settle = 0;
  std::string reason;  // why unknown when no interval could be formed
};

// Times of one pair, kind and view group (RoundTimes, audit/speed_timing.h), the same number of
// rounds for every primitive and side; control may be empty (no control). Throws
// std::invalid_argument for sides of different shapes.
SpeedComparison compare_speed(const RoundTimes& baseline_us, const RoundTimes& current_us,
                              const RoundTimes& control_us, double threshold);

// The ratio's estimate and 95% interval from per-round log ratios (see above): exp(mean) and exp
// of Student's t interval; NaN interval with fewer than 2 rounds. Exposed for tests.
struct RoundInterval {
  double ratio = 0, low = 0, high = 0;
};
RoundInterval round_interval(const std::vector<double>& log_ratios);

// "1.310x [1.250, 1.380]" of a ratio and its interval; "-" when undefined.
std::string speed_ratio_text(double ratio, double low, double high);

// Per round r, the Hodges-Lehmann estimate of the paired log ratios log(over[i][r] / under[i][r])
// over the primitives i: the per-round statistic round_interval summarises. Same shapes required.
std::vector<double> round_log_ratios(const RoundTimes& over, const RoundTimes& under);

struct SpeedAudit {
  bool performed = false;
  SpeedOptions options;
  std::vector<SpeedComparison> comparisons;  // by pair, kind, view group
  std::vector<std::string> errors;           // sides that could not be timed, and why
  std::size_t processes = 0;                 // timing processes started
  double seconds = 0;                        // their wall time
  std::size_t count(SpeedVerdict v) const;
};

// Sets welch_p_holm and levene_p_holm over every defined speed test.
void adjust_speed_tests(std::vector<SpeedComparison>& comparisons);

// Times every pair of an audit (the measurement above, audit/speed_timing.h) and compares them:
// per pair one interleaved timing of baseline, current and control. Ranges stop before a
// primitive `avoid` knows to crash or hang. `progress` (may be empty) gets one line per process.
// A side that cannot be timed (its driver is gone, its process failed) leaves its pair's groups
// `unknown` and its error in SpeedAudit::errors.
SpeedAudit audit_speed(const RunIdentity& baseline, const RunIdentity& current,
                       const std::vector<PlatformPair>& pairs, const KnownFailures& avoid,
                       const SpeedOptions& options,
                       const std::function<void(const std::string&)>& progress = {});

}  // namespace ra::audit
