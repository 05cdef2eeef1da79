// audit_speed (audit/speed_audit.h): which primitives are timed, on which sides, and how the
// per-primitive times become one comparison per pair, kind and view group.
#include <algorithm>
#include <cstdio>
#include <map>

#include "analysis/run_records.h"
#include "audit/speed_audit.h"
#include "stats/descriptive.h"

namespace ra::audit {
namespace {

// [0, per_view) of every kind and view the experiment draws, cut before the first primitive
// known to crash or hang on either platform of the pair.
std::vector<TimingRange> timing_ranges(const rundir::Experiment& exp, const PlatformPair& pair,
                                       const KnownFailures& avoid, uint64_t per_view) {
  std::vector<TimingRange> out;
  for (geometry::Kind kind : {geometry::Kind::kPoint, geometry::Kind::kLine,
                              geometry::Kind::kTriangle})
    for (const geometry::View& v : exp.views) {
      uint64_t end = std::min(per_view, exp.counts[std::size_t(kind)]);
      for (const std::string& platform : {pair.baseline, pair.current})
        while (end > 0 && avoid.hits(platform, kind, v.id, 0, end)) --end;
      if (end > 0) out.push_back({kind, v.id, 0, end});
    }
  return out;
}

}  // namespace

SpeedAudit audit_speed(const RunIdentity& baseline, const RunIdentity& current,
                       const std::vector<PlatformPair>& pairs, const KnownFailures& avoid,
                       const SpeedOptions& options,
                       const std::function<void(const std::string&)>& progress) {
  SpeedAudit audit;
  audit.performed = true;
  audit.options = options;
  const rundir::Experiment& exp = current.experiment;
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const PlatformPair& pair = pairs[p];
    const std::vector<TimingRange> ranges = timing_ranges(exp, pair, avoid, options.per_view);
    const std::vector<TimingSide> sides = {
        {"baseline", pair.baseline, baseline.dir, "", true},
        {"current", pair.current, current.dir, "", true},
        {"control", pair.baseline, baseline.dir, "", true}};
    TimingOptions to;
    to.repeats = options.repeats;
    to.program = options.program;
    const TimingResult t = time_interleaved(
        sides, ranges, to, [&](int round, std::size_t side, double seconds) {
          if (!progress) return;
          char line[256];
          (void)side;
          std::snprintf(line, sizeof line,
                        "timing %s: round %d of %d (baseline, current and control): %.1f s",
                        pair.label().c_str(), round + 1, options.repeats, seconds);
          progress(line);
        });
    audit.seconds += t.seconds;
    for (const auto& order : t.order) audit.processes += order.size();
    bool failed = false;
    for (std::size_t s = 0; s < sides.size(); ++s)
      if (!t.sides[s].error.empty()) {
        audit.errors.push_back(pair.label() + ": the " + sides[s].label + " side (" +
                               sides[s].platform + ") could not be timed: " + t.sides[s].error);
        failed = true;
      }

    // Per kind and view group: the primitives timed on every side.
    struct Samples {
      RoundTimes base, cur, ctl;
    };
    std::map<std::pair<int, int>, std::vector<TimedKey>> group_keys;
    for (const TimingRange& r : ranges) {
      int group = 0;
      for (const geometry::View& v : exp.views)
        if (v.id == r.view) group = v.group;
      std::vector<TimedKey>& keys = group_keys[{int(r.kind), group}];
      for (uint64_t i = r.begin; i < r.end; ++i) keys.push_back({int(r.kind), r.view, i});
    }
    std::map<std::pair<int, int>, Samples> groups;
    for (const auto& [key, keys] : group_keys) {
      Samples& g = groups[key];
      if (failed) continue;
      std::vector<RoundTimes> t3 =
          common_round_times({&t.sides[0], &t.sides[1], &t.sides[2]}, keys, options.repeats);
      g.base = std::move(t3[0]), g.cur = std::move(t3[1]), g.ctl = std::move(t3[2]);
    }
    for (const auto& [key, g] : groups) {
      SpeedComparison c = compare_speed(g.base, g.cur, g.ctl, options.threshold);
      c.pair = p;
      c.platform = pair.current;
      c.baseline_platform = pair.baseline;
      c.kind = geometry::Kind(key.first);
      c.view_group = key.second;
      c.group = analysis::view_group_label(key.second);
      if (failed)
        c.reason = "not timed: a side could not be drawn";
      else if (g.base.empty())
        c.reason = "no drawing time: the platforms do not time their drawing";
      audit.comparisons.push_back(std::move(c));
    }
  }
  adjust_speed_tests(audit.comparisons);
  return audit;
}

}  // namespace ra::audit
