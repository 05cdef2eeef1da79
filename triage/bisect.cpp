// The bisection loop (see the header).
#include "triage/bisect.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>

#include "rundir/run_folder.h"
#include "builds/build_slots.h"
#include "builds/git_command.h"
#include "triage/bisect_inputs.h"
#include "triage/bisect_judging.h"
#include "triage/bisect_plan.h"
#include "triage/bisect_report.h"
#include "triage/bisect_rounds.h"
#include "triage/bisect_state.h"
#include "triage/bisect_step.h"
#include "util/duration_text.h"
#include "util/errors.h"
#include "util/interrupt.h"

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace ra::triage {
namespace {

using builds::git;
using builds::GitResult;

std::string git_ok(const std::string& dir, const std::vector<std::string>& args,
                   const std::string& what) {
  const GitResult g = git(dir, args);
  if (!g.ok) throw util::UserError("bisect: " + what + " failed in " + dir + ":\n" + g.out);
  return g.out;
}

// One invocation of the bisection: its inputs checked, its state, and the steps of the loop.
class Bisection {
 public:
  Bisection(const BisectOptions& options, const std::function<void(const std::string&)>& progress)
      : o_(options), progress_(progress) {}

  BisectResult run() {
    const auto t_start = Clock::now();
    const CheckedInputs in = check_bisect_inputs(o_, st_.result);
    git_dir_ = in.git_dir;
    good_ = in.good;
    bad_ = in.bad;
    const auto lock = builds::lock_source_tree(o_.source, "bisect");
    // Worktrees a killed --ways bisection left are removed, whatever this one's --ways.
    std::error_code ec;
    if (fs::is_directory(git_dir_ + "/renderaudit-bisect", ec)) builds::BuildSlots{o_.source};
    load_state();
    util::InterruptScope interrupts;
    // The tree back on its branch however this ends (a step leaves it at a commit).
    // `original` is a branch name or a hash (checked where it is read), given to git as a revision.
    struct Restore {
      std::string dir, original;
      ~Restore() {
        if (git(dir, {"rev-parse", "HEAD"}).out !=
                git(dir, {"rev-parse", "--verify", "--quiet", "--end-of-options", original}).out ||
            !git(dir, {"symbolic-ref", "-q", "HEAD"}).ok)
          git(dir, {"checkout", "-q", original, "--"});
      }
    } restore{o_.source, st_.result.original_head};
    line_commits();
    draw_references();
    time_references();
    attribute();
    say(rounds_summary(st_.result));
    BisectResult& r = st_.result;
    r.total_build_s = r.good.build_s + r.bad.build_s;
    for (const BisectStep& s : r.steps) r.total_build_s += s.build_s;
    r.seconds = std::chrono::duration<double>(Clock::now() - t_start).count();
    save();
    r.report_path = rundir::run_folder::bisection_md(o_.out_dir);
    write_bisect_report(o_, r, judged_, progress_ ? progress_ : [](const std::string&) {});
    return r;
  }

 private:
  void say(const std::string& s) const {
    if (progress_) progress_(s);
  }
  std::function<void(const std::string&)> say_fn() const {
    return [this](const std::string& s) { say(s); };
  }
  void save() const { save_bisect_state(st_.result.json_path, st_); }

  // A drawing read back from bisect.json holds exactly the primitives its step drew: the ends the
  // whole selection, a step those the ends do not draw alike.
  void require_drawn(const BisectStep& s, const std::string& key,
                     const std::vector<BisectPrimitive>& drawn) const {
    const auto bad = [&](const std::string& label, const std::string& what) {
      throw util::UserError("bisect: " + st_.result.json_path + ": '" + key +
                            ".drawing.primitives[\"" + label + "\"]' " + what +
                            "; move the file away to start the bisection again");
    };
    std::set<std::string> labels;
    for (const BisectPrimitive& p : drawn) {
      labels.insert(p.label());
      if (!s.drawing.hashes.count(p.label())) bad(p.label(), "is missing");
    }
    for (const auto& [label, hash] : s.drawing.hashes)
      if (!labels.count(label)) bad(label, "is not a primitive this step drew");
  }

  // The steps of an earlier invocation with the same inputs; the tree's branch restored when
  // that invocation was killed at a step.
  void load_state() {
    st_.result.json_path = rundir::run_folder::bisection(o_.out_dir);
    nlohmann::json selection_ids = nlohmann::json::array();
    for (const BisectPrimitive& p : st_.result.selection) selection_ids.push_back(p.label());
    st_.inputs = {{"run", fs::weakly_canonical(o_.run_dir).string()},
                  {"baseline_run", o_.baseline_run.empty()
                                       ? ""
                                       : fs::weakly_canonical(o_.baseline_run).string()},
                  {"source", o_.source},
                  {"good", good_},
                  {"bad", bad_},
                  {"paths", o_.paths},
                  {"platform", o_.platform},
                  {"good_platform", o_.good_platform},
                  {"bad_platform", o_.bad_platform},
                  {"selection", selection_ids},
                  {"llvm_config", o_.build.llvm_config},
                  {"meson_options", o_.build.meson_options},
                  {"build_command", o_.build.build_command}};
    if (o_.speed.enabled)
      st_.inputs["speed"] = {{"repeats", o_.speed.repeats},
                             {"per_view", o_.speed.per_view},
                             {"threshold", o_.speed.threshold}};
    std::error_code ec;
    // A bisection of an older renderaudit (git bisect) killed on the way: git knows the branch.
    if (fs::exists(git_dir_ + "/BISECT_START", ec)) git(o_.source, {"bisect", "reset", "-q"});
    const GitResult branch = git(o_.source, {"symbolic-ref", "-q", "--short", "HEAD"});
    st_.result.original_head = branch.ok ? branch.out : git(o_.source, {"rev-parse", "HEAD"}).out;
    if (!fs::exists(st_.result.json_path, ec)) {
      save();  // the branch recorded before any checkout, for a resume after kill -9
      return;
    }
    BisectState old = load_bisect_state(st_.result.json_path);
    if (old.inputs.contains("speed") && !st_.inputs.contains("speed"))
      throw util::UserError("bisect: " + st_.result.json_path +
                            " holds a bisection of drawing time too (--speed); repeat its "
                            "--speed options, choose another --out, or remove it to start again");
    for (const auto& [k, v] : st_.inputs.items())
      if (!old.inputs.contains(k) || old.inputs[k] != v)
        throw util::UserError("bisect: " + st_.result.json_path +
                              " holds a bisection of other inputs ('" + k +
                              "' differs); choose another --out, or remove it to start again");
    // Only a detached HEAD is a step's checkout; a branch is where the person put the tree.
    if (!branch.ok && !old.result.original_head.empty() &&
        old.result.original_head != st_.result.original_head) {
      say("returning " + o_.source + " to " + old.result.original_head +
          ", where the interrupted bisection found it");
      git_ok(o_.source, {"checkout", "-q", old.result.original_head, "--"}, "git checkout");
      st_.result.original_head = old.result.original_head;
    }
    st_.result.steps = old.result.steps;
    st_.result.rounds = old.result.rounds;
    st_.result.good = old.result.good;
    st_.result.bad = old.result.bad;
    st_.result.speed_ends = old.result.speed_ends;
    say("resuming " + st_.result.json_path + ": " + std::to_string(st_.result.steps.size()) +
        " steps built");
  }

  // The commits from the good ref (position 0) to the bad ref, first parents only.
  void line_commits() {
    std::vector<std::string> args = {"rev-list", "--first-parent", "--reverse", bad_, "^" + good_};
    if (!o_.paths.empty()) {
      args.push_back("--");
      args.insert(args.end(), o_.paths.begin(), o_.paths.end());
    }
    const std::string out = git_ok(o_.source, args, "git rev-list");
    line_ = {good_};
    for (std::size_t at = 0; at < out.size();) {
      const std::size_t nl = std::min(out.find('\n', at), out.size());
      if (nl > at) line_.push_back(out.substr(at, nl - at));
      at = nl + 1;
    }
    if (line_.back() != bad_) line_.push_back(bad_);
    st_.result.commits_in_range = line_.size() - 1;
    std::set<std::size_t> positions;
    for (std::size_t i = 0; i < st_.result.steps.size(); ++i) {
      const BisectStep& s = st_.result.steps[i];
      const std::string key = "steps[" + std::to_string(i) + "].position";
      if (s.position >= line_.size() || line_[s.position] != s.commit)
        throw util::UserError("bisect: " + st_.result.json_path + ": '" + key +
                              "' does not hold its commit on today's line of commits "
                              "(the history changed?); move the file away to start again");
      if (s.position == 0 || s.position + 1 == line_.size() || !positions.insert(s.position).second)
        throw util::UserError("bisect: " + st_.result.json_path + ": '" + key +
                              "' is an end or a step already built (each commit between the ends "
                              "is built once); move the file away to start again");
    }
  }

  // The good and the bad ref drawn; primitives both draw alike say nothing about the change.
  void draw_references() {
    for (auto [ref, commit, step, role, position] :
         {std::tuple{o_.good_ref, good_, &st_.result.good, "good ref", std::size_t(0)},
          std::tuple{o_.bad_ref, bad_, &st_.result.bad, "bad ref", line_.size() - 1}}) {
      if (step->commit == commit && step->error.empty() && !step->drawing.hashes.empty()) {
        require_drawn(*step, role == std::string("good ref") ? "good" : "bad", st_.result.selection);
        continue;
      }
      *step = BisectStep{};
      step->role = role;
      step->commit = commit;
      step->position = position;
      say(std::string(role) + " " + ref + " (" + short_hash(commit) + ")");
      build_and_draw_step(o_, st_.result.selection, *step, say_fn());
      if (step->build.empty())
        throw util::UserError("bisect: the " + std::string(role) + " " + ref +
                              " cannot be built: " + step->error);
      if (!step->drawing.error.empty())
        throw util::UserError("bisect: the build of the " + std::string(role) + " " + ref +
                              " cannot draw the selection with " + o_.platform + ": " +
                              step->drawing.error);
      save();
    }
    split_by_ends(st_.result.selection, st_.result.good.drawing, st_.result.bad.drawing, judged_,
                  st_.result.dropped);
    if (judged_.empty() && !o_.speed.enabled)
      throw util::UserError("bisect: the builds of " + o_.good_ref + " and " + o_.bad_ref +
                            " draw all " + std::to_string(st_.result.selection.size()) +
                            " selected primitives alike on " + o_.platform +
                            ": the change is not between these refs (or not in this platform)");
    if (judged_.empty()) return;  // drawing time only: time_references() decides
    if (!st_.result.dropped.empty())
      say(std::to_string(st_.result.dropped.size()) + " of " +
          std::to_string(st_.result.selection.size()) +
          " selected primitives are drawn alike by both refs and are left out");
    say(std::to_string(judged_.size()) + " primitives to attribute over " +
        std::to_string(line_.size() - 1) + " commits (" + st_.result.selection_rule + ")");
  }

  // --speed: the ends timed (the good ref, the bad ref, the good ref again); the groups that
  // moved are attributed beside the primitives.
  void time_references() {
    BisectResult& r = st_.result;
    if (o_.speed.enabled) {
      if (r.speed_ends.empty()) {
        const auto t0 = Clock::now();
        r.speed_ends = time_ends(o_, speed_groups(o_), r.good.build_dir, r.bad.build_dir, say_fn());
        say("timed the refs in " +
            util::duration_text(std::chrono::duration<double>(Clock::now() - t0).count()));
        save();
      }
      for (const SpeedAtEnds& e : r.speed_ends) {
        const audit::SpeedComparison& c = e.comparison;
        std::string line = e.group.label() + ": " + audit::speed_ratio_text(c.ratio, c.low, c.high) +
                           " " + audit::speed_verdict_name(c.verdict) + " (control " +
                           audit::speed_ratio_text(c.control_ratio, c.control_low, c.control_high) +
                           ")";
        if (c.verdict == audit::SpeedVerdict::kUnknown)
          line += !c.reason.empty() ? ": not attributed, " + c.reason
                  : c.repeats_to_settle > 0
                      ? ": not attributed; about " + std::to_string(c.repeats_to_settle) +
                            " --speed-repeats would settle it"
                      : ": not attributed; the estimate sits at the band's edge, more repeats "
                        "would not settle it";
        say(line);
        if (e.moved()) moved_.push_back(e);
      }
    }
    if (judged_.empty() && moved_.empty())
      throw util::UserError(
          "bisect: the builds of " + o_.good_ref + " and " + o_.bad_ref + " draw all " +
          std::to_string(r.selection.size()) + " selected primitives alike on " + o_.platform +
          " and no group's drawing time moved beyond the threshold: nothing to attribute between "
          "these refs (or not in this platform)");
  }

  // The pixel hashes of a step's primitives and the places of its drawing times, as the plan reads
  // them (a time unknown at the step is left out: unknown there).
  std::map<std::string, uint64_t> observation(const BisectStep& s) const {
    std::map<std::string, uint64_t> out = judged_hashes(judged_, s.drawing);
    for (const StepTime& t : s.speed)
      if (t.place != TimePlace::kUnknown && tracked(t.group))
        out[t.group.label()] = t.place == TimePlace::kAsGood ? kGoodTime : kBadTime;
    return out;
  }
  bool tracked(const SpeedGroup& g) const {
    if (given_up_.count(g.label())) return false;
    for (const SpeedAtEnds& e : moved_)
      if (e.group == g) return true;
    return false;
  }

  // A group unknown at kMaxUnknownSteps steps is given up (its time moved in small steps, or the
  // machine is too noisy to place it): reported unattributed with its range.
  void count_unknowns(const BisectStep& s, AttributionPlan& plan,
                      std::map<std::string, int>& unknowns) {
    for (const StepTime& t : s.speed) {
      const std::string label = t.group.label();
      if (t.place != TimePlace::kUnknown || !tracked(t.group)) continue;
      if (++unknowns[label] < kMaxUnknownSteps) continue;
      SpeedUnattributed u{t.group, line_.front(), line_.back(), {}, "", ""};
      for (const AttributionPlan::Change& c : plan.changes())
        if (c.label == label && !c.resolved) u.from = line_[c.from], u.to = line_[c.to];
      u.why = "its time could not be placed between the ends' at " +
              std::to_string(kMaxUnknownSteps) +
              " steps: it moved in several smaller steps, or the machine is too noisy (more "
              "--speed-repeats)";
      st_.result.speed_unattributed.push_back(u);
      plan.forget(label);
      given_up_.insert(label);
      say(label + ": given up, " + u.why);
    }
  }

  // The moved groups whose unresolved range holds `position`.
  std::vector<SpeedGroup> groups_to_time(const AttributionPlan& plan, std::size_t position) const {
    std::vector<SpeedGroup> out;
    for (const SpeedAtEnds& e : moved_) {
      if (!tracked(e.group)) continue;
      for (const AttributionPlan::Change& c : plan.changes())
        if (c.label == e.group.label() && !c.resolved && c.from < position && position < c.to)
          out.push_back(e.group);
    }
    return out;
  }

  // Builds until every change sits between two neighbouring commits.
  void attribute() {
    AttributionPlan plan(line_.size() - 1);
    std::map<std::string, uint64_t> good = judged_hashes(judged_, st_.result.good.drawing),
                                    bad = judged_hashes(judged_, st_.result.bad.drawing);
    for (const SpeedAtEnds& e : moved_) {
      good[e.group.label()] = kGoodTime;
      bad[e.group.label()] = kBadTime;
    }
    plan.observe(0, good);
    plan.observe(line_.size() - 1, bad);
    st_.result.speed_unattributed.clear();
    std::map<std::string, int> unknowns;
    for (std::size_t i = 0; i < st_.result.steps.size(); ++i) {
      const BisectStep& s = st_.result.steps[i];
      if (s.error.empty()) {
        require_drawn(s, "steps[" + std::to_string(i) + "]", judged_);
        plan.observe(s.position, observation(s));
        count_unknowns(s, plan, unknowns);
      } else {
        plan.fail(s.position);
      }
    }
    if (o_.ways > 1 || o_.slurm) {
      RoundContext c{o_, line_, judged_, st_.result, plan, say_fn(), [this] { save(); },
                     [&](BisectStep& s) {
                       s.summary = step_summary(s);
                       plan.observe(s.position, observation(s));
                     }};
      run_rounds(c);
    } else {
      one_at_a_time(plan, unknowns);
    }
    collect_culprits(plan, line_, judged_, o_.source, st_.result, say_fn());
    collect_speed_culprits(plan);
  }

  // --ways 1: a round is one build, in the tree itself (its incremental build folder).
  void one_at_a_time(AttributionPlan& plan, std::map<std::string, int>& unknowns) {
    RoundContext rounds{o_, line_, judged_, st_.result, plan, say_fn(), {}, {}};
    double step_seconds = 0;
    int fresh_steps = 0;
    while (const auto position = plan.next()) {
      util::throw_if_interrupted();
      BisectStep s;
      s.role = "step";
      s.position = *position;
      s.commit = line_[*position];
      // Steps left: a binary search of each unresolved range.
      std::set<std::pair<std::size_t, std::size_t>> gaps;
      for (const AttributionPlan::Change& c : plan.changes())
        if (!c.resolved) gaps.insert({c.from, c.to});
      std::size_t left = 0;
      for (const auto& [from, to] : gaps) left += std::size_t(std::ceil(std::log2(double(to - from))));
      std::string eta = " (" + std::to_string(gaps.size()) + " unresolved range" +
                        (gaps.size() == 1 ? "" : "s") + ", roughly " + std::to_string(left) +
                        (left == 1 ? " step" : " steps") + " to go";
      if (fresh_steps > 0) eta += ", about " + util::duration_text(step_seconds / fresh_steps * left);
      eta += ")";
      const auto t0 = Clock::now();
      const std::size_t round = begin_round(rounds, {*position}, "tree").round - 1;
      say(round_line(st_.result.rounds[round]));
      say("step " + std::to_string(st_.result.steps.size() + 1) + eta + ": " + short_hash(s.commit) +
          " " + git(o_.source, {"log", "-1", "--format=%s", s.commit}).out);
      const std::vector<SpeedGroup> timed = groups_to_time(plan, s.position);
      build_and_draw_step(o_, judged_, s, say_fn());
      if (s.error.empty()) {
        if (!timed.empty()) {
          const auto t1 = Clock::now();
          s.speed = time_step(o_, timed, st_.result.good.build_dir, s.build_dir,
                              st_.result.bad.build_dir, say_fn());
          s.time_s = std::chrono::duration<double>(Clock::now() - t1).count();
        }
        s.summary = step_summary(s);
        plan.observe(s.position, observation(s));
        say("  drew " + s.summary);
        count_unknowns(s, plan, unknowns);
      } else {
        plan.fail(s.position);
        st_.result.rounds[round].failed.push_back(s.commit);
        say("  skipped for every primitive: " + s.error);
      }
      st_.result.steps.push_back(s);
      step_seconds += std::chrono::duration<double>(Clock::now() - t0).count();
      ++fresh_steps;
      BisectRound& r = st_.result.rounds[round];
      r.build_wall_s = s.build_s;
      r.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
      r.finished = true;
      save();
    }
  }

  // What a step drew, in words: its primitives against the ends, then its drawing times.
  std::string step_summary(const BisectStep& s) const {
    std::string out = judged_.empty() ? std::string()
                                      : drawing_summary(judged_, st_.result.good.drawing,
                                                        st_.result.bad.drawing, s.drawing);
    for (const StepTime& t : s.speed) {
      char share[64] = "";
      if (std::isfinite(t.share))
        std::snprintf(share, sizeof share, ", %.0f%% of the way", 100 * t.share);
      out += std::string(out.empty() ? "" : "; ") + t.group.text() + " time " +
             time_place_name(t.place) + " (" +
             (t.note.empty() ? audit::speed_ratio_text(t.ratio, t.low, t.high) + " the good ref's" +
                                   share
                             : t.note) +
             ")";
    }
    return out;
  }

  // The moved groups' changes as speed culprits (each confirmed beside its git parent) and
  // what stays unattributed.
  void collect_speed_culprits(const AttributionPlan& plan) {
    BisectResult& r = st_.result;
    r.speed_culprits.clear();
    std::map<std::size_t, std::string> build_at = {{0, r.good.build_dir},
                                                   {line_.size() - 1, r.bad.build_dir}};
    for (const BisectStep& s : r.steps)
      if (s.error.empty()) build_at[s.position] = s.build_dir;
    std::map<std::size_t, SpeedCulprit> by_position;
    for (const SpeedAtEnds& e : moved_) {
      if (!tracked(e.group)) continue;
      for (const AttributionPlan::Change& c : plan.changes()) {
        if (c.label != e.group.label()) continue;
        if (!c.resolved) {
          SpeedUnattributed u{e.group, line_[c.from], line_[c.to], {}, "", ""};
          for (std::size_t p : c.candidates) u.candidates.push_back(line_[p]);
          u.why = "only commits that failed to build lie between";
          r.speed_unattributed.push_back(u);
          continue;
        }
        // Back from the bad ref's time to the good ref's (a step misplaced, or a change undone
        // later): the other direction.
        const bool onward = c.hash_before == kGoodTime;
        const audit::SpeedVerdict other = e.comparison.verdict == audit::SpeedVerdict::kSlower
                                              ? audit::SpeedVerdict::kFaster
                                              : audit::SpeedVerdict::kSlower;
        SpeedCulprit& k = by_position[c.to];
        k.moves.push_back({e.group,
                           onward ? e.comparison.verdict : other,
                           {},
                           "",
                           onward ? TimePlace::kAsBad : TimePlace::kAsGood});
      }
    }
    for (auto& [position, k] : by_position) {
      BisectStep info;
      info.commit = line_[position];
      describe_commit(o_.source, info);
      k.commit = info.commit;
      k.subject = info.subject;
      k.date = info.date;
      k.previous = line_[position - 1];
      confirm_speed_culprit(
          o_, k,
          {r.good.build_dir, build_at.at(position - 1), build_at.at(position), r.bad.build_dir},
          r.speed_unattributed, say_fn());
      if (!k.moves.empty()) r.speed_culprits.push_back(k);
    }
  }

  BisectOptions o_;
  std::function<void(const std::string&)> progress_;
  BisectState st_;
  std::string git_dir_, good_, bad_;
  std::vector<std::string> line_;         // position -> commit
  std::vector<BisectPrimitive> judged_;  // the selection less what both refs draw alike
  std::vector<SpeedAtEnds> moved_;        // --speed: the groups whose drawing time moved
  std::set<std::string> given_up_;        // their labels no step could place
  // A group's drawing time in the plan: a two-valued "hash" (bisect_plan.h).
  static constexpr uint64_t kGoodTime = 1, kBadTime = 2;
  static constexpr int kMaxUnknownSteps = 3;
};

}  // namespace

BisectResult run_bisect(const BisectOptions& options,
                        const std::function<void(const std::string&)>& progress) {
  return Bisection(options, progress).run();
}

}  // namespace ra::triage
