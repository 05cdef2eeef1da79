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

// The median of a primitive's rounds; NaN when it has none or a time that is not positive (a
// platform that does not time its drawing).
double primitive_time(const SideTiming& side, const TimedKey& key) {
  const auto it = side.render_us.find(key);
  if (it == side.render_us.end() || it->second.empty()) return -1;
  for (double t : it->second)
    if (!(t > 0)) return -1;
  return stats::median(it->second);
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
          std::snprintf(line, sizeof line, "timing %s: round %d of %d, %s (%s): %.1f s",
                        pair.label().c_str(), round + 1, options.repeats, sides[side].label.c_str(),
                        sides[side].platform.c_str(), seconds);
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
      std::vector<double> base, cur, ctl;
    };
    std::map<std::pair<int, int>, Samples> groups;
    for (const TimingRange& r : ranges) {
      const geometry::View* view = nullptr;
      for (const geometry::View& v : exp.views)
        if (v.id == r.view) view = &v;
      Samples& g = groups[{int(r.kind), view ? view->group : 0}];
      if (failed) continue;
      for (uint64_t i = r.begin; i < r.end; ++i) {
        const TimedKey key{int(r.kind), r.view, i};
        const double b = primitive_time(t.sides[0], key), c = primitive_time(t.sides[1], key),
                     a = primitive_time(t.sides[2], key);
        if (b > 0 && c > 0 && a > 0) g.base.push_back(b), g.cur.push_back(c), g.ctl.push_back(a);
      }
    }
    for (const auto& [key, g] : groups) {
      SpeedComparison c = compare_speed(g.base, g.cur, g.ctl, options.threshold, options.repeats);
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
