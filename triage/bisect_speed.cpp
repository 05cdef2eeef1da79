// Drawing time in a bisection (see the header).
#include "triage/bisect_speed.h"

#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <stdexcept>

#include "analysis/view_equivalence.h"
#include "builds/git_command.h"
#include "rundir/run_experiment.h"
#include "stats/descriptive.h"
#include "triage/bisect.h"
#include "triage/bisect_step.h"
#include "util/errors.h"
#include "util/interrupt.h"

namespace ra::triage {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// One side of a bisection's timing: a build drawn through the bisection's platform.
audit::TimingSide build_side(const BisectOptions& o, const std::string& label,
                             const std::string& build_dir) {
  return {label, o.platform + "@" + kStepBuild, o.run_dir,
          bisect_step_experiment(o.run_dir, build_dir), false};
}

// The ranges (the first per_view primitives of each kind and view) and timed keys of each group.
struct GroupSample {
  std::vector<audit::TimingRange> ranges;
  std::map<SpeedGroup, std::vector<audit::TimedKey>> keys;
};

GroupSample sample_of(const BisectOptions& o, const std::vector<SpeedGroup>& groups) {
  const rundir::Experiment exp = rundir::load_run_experiment(o.run_dir);
  GroupSample s;
  for (const SpeedGroup& g : groups)
    for (const geometry::View& v : exp.views) {
      if (v.group != g.view_group) continue;
      if (!o.views.empty() && std::find(o.views.begin(), o.views.end(), v.id) == o.views.end())
        continue;
      const uint64_t end = std::min<uint64_t>(o.speed.per_view, exp.counts[std::size_t(g.kind)]);
      if (end == 0) continue;
      s.ranges.push_back({g.kind, v.id, 0, end});
      for (uint64_t i = 0; i < end; ++i) s.keys[g].push_back({int(g.kind), v.id, i});
    }
  return s;
}

// The sides timed over `groups`, `say` told after each round.
audit::TimingResult time_sides(const BisectOptions& o, const std::vector<audit::TimingSide>& sides,
                               const GroupSample& sample, const std::string& what,
                               const std::function<void(const std::string&)>& say) {
  audit::TimingOptions to;
  to.repeats = o.speed.repeats;
  double elapsed = 0;
  // A line per round only once the timing is slow enough for a person to wait on it.
  audit::TimingResult t =
      audit::time_interleaved(sides, sample.ranges, to, [&](int round, std::size_t, double s) {
        elapsed += s;
        if (elapsed < 10 || round + 1 == o.speed.repeats) return;
        char line[256];
        std::snprintf(line, sizeof line, "  timing %s: round %d of %d: %.1f s", what.c_str(),
                      round + 1, o.speed.repeats, s);
        say(line);
      });
  util::throw_if_interrupted();
  char line[256];
  std::snprintf(line, sizeof line, "  timed %s: %d rounds of %zu processes in %.1f s", what.c_str(),
                o.speed.repeats, sides.size(), t.seconds);
  say(line);
  return t;
}

std::string side_errors(const std::vector<audit::TimingSide>& sides, const audit::TimingResult& t) {
  std::string out;
  for (std::size_t s = 0; s < sides.size(); ++s)
    if (!t.sides[s].error.empty())
      out += (out.empty() ? "" : "; ") + sides[s].label + ": " + t.sides[s].error;
  return out;
}

std::vector<double> sided(const std::vector<double>& a, const std::vector<double>& b, double sign) {
  std::vector<double> v(a.size());
  for (std::size_t r = 0; r < a.size(); ++r) v[r] = sign * (a[r] - b[r] / 2);
  return v;
}

// The timing of a culprit's moves beside `beside_build`.
void confirm_moves(const BisectOptions& o, SpeedCulprit& c, const std::string& beside_build,
                   const std::string& culprit_build,
                   const std::function<void(const std::string&)>& say) {
  std::vector<SpeedGroup> groups;
  for (const SpeedCulprit::Move& m : c.moves) groups.push_back(m.group);
  const GroupSample sample = sample_of(o, groups);
  const std::vector<audit::TimingSide> sides = {build_side(o, "the commit before", beside_build),
                                                build_side(o, "the culprit", culprit_build),
                                                build_side(o, "the control", beside_build)};
  const audit::TimingResult t = time_sides(
      o, sides, sample, c.commit.substr(0, 12) + " beside " + c.beside.substr(0, 12), say);
  const std::string e = side_errors(sides, t);
  for (SpeedCulprit::Move& m : c.moves) {
    if (!e.empty()) {
      m.error = e;
      continue;
    }
    const auto keys = sample.keys.find(m.group);
    const std::vector<audit::RoundTimes> times = audit::common_round_times(
        {&t.sides[0], &t.sides[1], &t.sides[2]},
        keys == sample.keys.end() ? std::vector<audit::TimedKey>{} : keys->second, o.speed.repeats);
    m.confirmation = audit::compare_speed(times[0], times[1], times[2], o.speed.threshold);
    m.confirmation.kind = m.group.kind;
    m.confirmation.view_group = m.group.view_group;
    m.confirmation.group = analysis::view_group_label(m.group.view_group);
  }
}

// The moves whose time the culprit's git parent already has (placed where the culprit is): they
// happened in a commit the paths left out, between `c.previous` and the parent. Each leaves `c`
// for `unattributed`, with the bisection without paths that would name it.
void move_out_what_the_parent_has(const BisectOptions& o, SpeedCulprit& c,
                                  std::vector<SpeedUnattributed>& unattributed) {
  BisectOptions outside = o;
  outside.good_ref = c.previous;
  outside.bad_ref = c.beside;
  outside.paths.clear();
  outside.kinds.clear();
  outside.out_dir = o.out_dir + "/before-" + short_hash(c.commit);
  std::vector<SpeedCulprit::Move> kept;
  std::vector<std::pair<SpeedCulprit::Move, StepTime>> moved_out;  // with the parent's place
  for (std::size_t i = 0; i < c.moves.size(); ++i) {
    if (i < c.parent_places.size() && c.parent_places[i].place == c.moves[i].at_culprit) {
      moved_out.push_back({c.moves[i], c.parent_places[i]});
      outside.kinds.push_back(geometry::kind_name(c.moves[i].group.kind));
    } else {
      kept.push_back(c.moves[i]);
    }
  }
  if (moved_out.empty()) return;
  std::sort(outside.kinds.begin(), outside.kinds.end());
  outside.kinds.erase(std::unique(outside.kinds.begin(), outside.kinds.end()), outside.kinds.end());
  const std::string count =
      builds::git(o.source, {"rev-list", "--first-parent", "--count", c.previous + ".." + c.beside})
          .out;
  // "N commits after PREVIOUS up to the parent": the parent itself when N is 1.
  const std::string where = count == "1" ? "the parent itself"
                                         : "one of the " + count + " commits after " +
                                               short_hash(c.previous) + " up to the parent";
  for (const auto& [m, t] : moved_out) {
    char place[96];
    std::snprintf(place, sizeof place, ", %.0f%% of the way", 100 * t.share);
    unattributed.push_back({m.group, c.previous, c.beside, {},
                            "its git parent " + short_hash(c.beside) + " draws it as " +
                                short_hash(c.commit) + " does (" + time_place_name(t.place) +
                                ": " + audit::speed_ratio_text(t.ratio, t.low, t.high) +
                                " the good ref's" + place + "): the move lies in " + where +
                                ", which the paths leave out",
                            bisect_command_line(outside)});
  }
  c.moves = kept;
}

}  // namespace

std::string SpeedGroup::text() const {
  return std::string(geometry::kind_plural(kind)) + ", view group " +
         analysis::view_group_label(view_group);
}

std::string SpeedGroup::label() const { return "drawing time of " + text(); }

const char* time_place_name(TimePlace p) {
  switch (p) {
    case TimePlace::kAsGood: return "as good";
    case TimePlace::kAsBad: return "as bad";
    case TimePlace::kUnknown: return "unknown";
  }
  return "unknown";
}

TimePlace parse_time_place(const std::string& name) {
  for (TimePlace p : {TimePlace::kAsGood, TimePlace::kAsBad, TimePlace::kUnknown})
    if (name == time_place_name(p)) return p;
  throw std::invalid_argument("not a place of a step's time: " + name);
}

StepTime place_step(const audit::RoundTimes& good, const audit::RoundTimes& step,
                    const audit::RoundTimes& bad) {
  StepTime t;
  t.ratio = t.low = t.high = t.share = t.share_low = t.share_high = kNaN;
  const std::size_t rounds = good.empty() ? 0 : good[0].size();
  t.repeats = int(rounds);
  if (good.empty() || step.size() != good.size() || bad.size() != good.size()) {
    t.note = "no primitive timed on every side";
    return t;
  }
  const std::vector<double> a = audit::round_log_ratios(step, good);
  const std::vector<double> b = audit::round_log_ratios(bad, good);
  const audit::RoundInterval ratio = audit::round_interval(a);
  t.ratio = ratio.ratio, t.low = ratio.low, t.high = ratio.high;
  const double mean_b = stats::mean_and_variance(b).mean;
  const double mean_a = stats::mean_and_variance(a).mean;
  if (rounds < 2 || !(std::fabs(mean_b) > 0)) {
    t.note = rounds < 2 ? "one round: an interval needs at least 2" : "the ends drew alike";
    return t;
  }
  // v_r > 0: the step is nearer the bad ref's time than the good ref's in round r.
  const std::vector<double> v = sided(a, b, mean_b > 0 ? 1.0 : -1.0);
  const stats::MeanVariance mv = stats::mean_and_variance(v);
  const boost::math::students_t dist(double(rounds - 1));
  const double half = boost::math::quantile(boost::math::complement(dist, 0.025)) *
                      std::sqrt(mv.variance / double(rounds));
  const double scale = std::fabs(mean_b);
  t.share = mean_a / mean_b;
  t.share_low = 0.5 + (mv.mean - half) / scale;
  t.share_high = 0.5 + (mv.mean + half) / scale;
  if (mv.mean - half > 0)
    t.place = TimePlace::kAsBad;
  else if (mv.mean + half < 0)
    t.place = TimePlace::kAsGood;
  return t;
}

std::vector<SpeedGroup> speed_groups(const BisectOptions& o) {
  const rundir::Experiment exp = rundir::load_run_experiment(o.run_dir);
  std::vector<SpeedGroup> out;
  for (geometry::Kind kind :
       {geometry::Kind::kPoint, geometry::Kind::kLine, geometry::Kind::kTriangle}) {
    if (exp.counts[std::size_t(kind)] == 0) continue;
    if (!o.kinds.empty() &&
        std::find(o.kinds.begin(), o.kinds.end(), geometry::kind_name(kind)) == o.kinds.end())
      continue;
    for (const geometry::View& v : exp.views) {
      if (!o.views.empty() && std::find(o.views.begin(), o.views.end(), v.id) == o.views.end())
        continue;
      const SpeedGroup g{kind, v.group};
      if (std::find(out.begin(), out.end(), g) == out.end()) out.push_back(g);
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<SpeedAtEnds> time_ends(const BisectOptions& o, const std::vector<SpeedGroup>& groups,
                                   const std::string& good_build, const std::string& bad_build,
                                   const std::function<void(const std::string&)>& say) {
  const GroupSample sample = sample_of(o, groups);
  const std::vector<audit::TimingSide> sides = {build_side(o, "the good ref", good_build),
                                                build_side(o, "the bad ref", bad_build),
                                                build_side(o, "the control", good_build)};
  const audit::TimingResult t = time_sides(o, sides, sample, "the refs (good, bad, good again)", say);
  if (const std::string e = side_errors(sides, t); !e.empty())
    throw util::UserError("bisect --speed: the drawing time of the refs cannot be measured: " + e);
  std::vector<SpeedAtEnds> out;
  std::vector<audit::SpeedComparison> comparisons;
  for (const SpeedGroup& g : groups) {
    const auto keys = sample.keys.find(g);
    const std::vector<audit::RoundTimes> times = audit::common_round_times(
        {&t.sides[0], &t.sides[1], &t.sides[2]},
        keys == sample.keys.end() ? std::vector<audit::TimedKey>{} : keys->second, o.speed.repeats);
    audit::SpeedComparison c = audit::compare_speed(times[0], times[1], times[2], o.speed.threshold);
    c.kind = g.kind;
    c.view_group = g.view_group;
    c.group = analysis::view_group_label(g.view_group);
    if (times[0].empty()) c.reason = "no drawing time: the platform does not time its drawing";
    comparisons.push_back(c);
  }
  audit::adjust_speed_tests(comparisons);
  for (std::size_t i = 0; i < groups.size(); ++i) out.push_back({groups[i], comparisons[i]});
  return out;
}

std::vector<StepTime> time_step(const BisectOptions& o, const std::vector<SpeedGroup>& groups,
                                const std::string& good_build, const std::string& step_build,
                                const std::string& bad_build,
                                const std::function<void(const std::string&)>& say) {
  const std::vector<audit::TimingSide> sides = {build_side(o, "the good ref", good_build),
                                                build_side(o, "the step", step_build),
                                                build_side(o, "the bad ref", bad_build)};
  std::vector<StepTime> out(groups.size());
  std::vector<audit::SideTiming> pooled;
  std::vector<std::size_t> undecided;
  for (std::size_t i = 0; i < groups.size(); ++i) undecided.push_back(i);
  int rounds = 0;
  // At most twice: Pinpoint's "unknown: measure more", then the plan moves to a neighbour.
  for (int attempt = 0; attempt < 2 && !undecided.empty(); ++attempt) {
    std::vector<SpeedGroup> now;
    for (std::size_t i : undecided) now.push_back(groups[i]);
    const GroupSample sample = sample_of(o, now);
    const audit::TimingResult t =
        time_sides(o, sides, sample, attempt == 0 ? "the step beside the refs"
                                                  : "the step again (undecided)", say);
    if (const std::string e = side_errors(sides, t); !e.empty()) {
      for (std::size_t i : undecided) {
        out[i].group = groups[i];
        out[i].place = TimePlace::kUnknown;
        out[i].note = "not timed: " + e;
      }
      return out;
    }
    if (pooled.empty())
      pooled = t.sides;
    else
      for (std::size_t s = 0; s < sides.size(); ++s) audit::append_rounds(pooled[s], t.sides[s]);
    rounds += o.speed.repeats;
    std::vector<std::size_t> still;
    for (std::size_t i : undecided) {
      const auto keys = sample.keys.find(groups[i]);
      const std::vector<audit::RoundTimes> times = audit::common_round_times(
          {&pooled[0], &pooled[1], &pooled[2]},
          keys == sample.keys.end() ? std::vector<audit::TimedKey>{} : keys->second, rounds);
      out[i] = place_step(times[0], times[1], times[2]);
      out[i].group = groups[i];
      if (out[i].place == TimePlace::kUnknown && out[i].note.empty()) still.push_back(i);
    }
    undecided = still;
  }
  return out;
}

void confirm_speed_culprit(const BisectOptions& o, SpeedCulprit& c, const CulpritBuilds& at,
                           std::vector<SpeedUnattributed>& unattributed,
                           const std::function<void(const std::string&)>& say) {
  c.beside = c.previous;
  std::string beside_build = at.previous;
  const builds::GitResult p =
      builds::git(o.source, {"rev-parse", "--verify", "--quiet", c.commit + "^1"});
  const std::string parent = p.ok ? p.out : "";
  if (!parent.empty() && parent != c.previous) {
    say("  its git parent " + short_hash(parent) + " is not the commit before it among those " +
        "touching the paths (" + short_hash(c.previous) + "): building and placing the parent");
    BisectStep step;
    step.role = "git parent";
    step.commit = parent;
    build_and_draw_step(o, {}, step, say);
    if (!step.error.empty()) {
      c.beside_note = "its git parent " + short_hash(parent) + " could not be built (" +
                      step.error + "), so it was timed beside " + short_hash(c.previous) +
                      ", the commit before it among those touching the paths";
    } else {
      c.beside = parent;
      beside_build = step.build_dir;
      std::vector<SpeedGroup> groups;
      for (const SpeedCulprit::Move& m : c.moves) groups.push_back(m.group);
      c.parent_places = time_step(o, groups, at.good, beside_build, at.bad, say);
      move_out_what_the_parent_has(o, c, unattributed);
    }
  }
  if (c.moves.empty()) return;
  say("confirming " + short_hash(c.commit) + " " + c.subject + " beside " + short_hash(c.beside));
  confirm_moves(o, c, beside_build, at.culprit, say);
}

std::vector<std::string> speed_culprit_lines(const SpeedCulprit& c, const std::string& lead) {
  std::vector<std::string> lines;
  for (audit::SpeedVerdict direction : {audit::SpeedVerdict::kSlower, audit::SpeedVerdict::kFaster}) {
    std::string groups;
    for (const SpeedCulprit::Move& m : c.moves) {
      if (m.direction != direction) continue;
      const audit::SpeedComparison& k = m.confirmation;
      groups += (groups.empty() ? "" : "; ") + m.group.text() + ": " +
                (m.error.empty() ? audit::speed_ratio_text(k.ratio, k.low, k.high)
                                 : "not confirmed, " + m.error);
    }
    if (groups.empty()) continue;
    lines.push_back(std::string("first ") + audit::speed_verdict_name(direction) + " commit: " +
                    c.commit + " " + c.subject + " (" + lead + groups + ")");
  }
  return lines;
}

}  // namespace ra::triage
