// The rounds of a bisection (see the header).
#include "triage/bisect_rounds.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <set>
#include <thread>

#include "builds/build_slots.h"
#include "builds/commit_builds.h"
#include "builds/slurm_builds.h"
#include "triage/bisect_step.h"
#include "util/duration_text.h"
#include "util/interrupt.h"

using Clock = std::chrono::steady_clock;

namespace ra::triage {

BisectRound& begin_round(RoundContext& c, const std::vector<std::size_t>& positions,
                         const std::string& where) {
  BisectRound r;
  r.round = c.result.rounds.size() + 1;
  r.ways = c.o.ways;
  r.where = where;
  for (std::size_t p : positions) r.commits.push_back(c.line[p]);
  r.unresolved = c.plan.unresolved();
  r.rounds_to_go = c.plan.rounds_to_go(c.o.ways);
  c.result.rounds.push_back(r);
  return c.result.rounds.back();
}

std::string round_line(const BisectRound& r) {
  std::string hashes;
  for (const std::string& commit : r.commits) hashes += (hashes.empty() ? "" : " ") + short_hash(commit);
  return "round " + std::to_string(r.round) + ": " + std::to_string(r.commits.size()) +
         (r.commits.size() == 1 ? " build (" : " builds (") + hashes + "), " +
         std::to_string(r.unresolved) + (r.unresolved == 1 ? " change" : " changes") +
         " unresolved, about " + std::to_string(r.rounds_to_go) +
         (r.rounds_to_go == 1 ? " round" : " rounds") + " to go";
}

std::string rounds_summary(const BisectResult& r) {
  double building = 0;
  for (const BisectRound& round : r.rounds) building += round.build_wall_s;
  return std::to_string(r.rounds.size()) + (r.rounds.size() == 1 ? " round, " : " rounds, ") +
         std::to_string(r.steps.size()) + (r.steps.size() == 1 ? " build, " : " builds, ") +
         util::duration_text(building) + " of building";
}

namespace {

// One round: its steps built (or taken from the cache), drawn and decided as they come.
class Round {
 public:
  Round(RoundContext& c, builds::BuildSlots& slots, builds::CommitBuilds& builds)
      : c_(c), slots_(slots), builds_(builds) {}

  void run(const std::vector<std::size_t>& positions) {
    const auto t0 = Clock::now();
    index_ = begin_round(c_, positions, c_.o.slurm ? "slurm" : "worktrees").round - 1;
    c_.say(round_line(c_.result.rounds[index_]));
    c_.save();
    steps_.assign(positions.size(), BisectStep{});
    std::vector<std::size_t> cached;
    for (std::size_t i = 0; i < positions.size(); ++i) {
      BisectStep& s = steps_[i];
      s.role = "step";
      s.position = positions[i];
      s.commit = c_.line[positions[i]];
      describe_commit(c_.o.source, s);
      slot_.push_back(slots_.check_out(i, s.commit));
      if (builds::cached_source_build(options(i))) cached.push_back(i);
    }
    // What the cache holds is drawn first: it may make some of the builds needless.
    for (std::size_t i : cached) finish(i, true, "", 0);
    std::vector<std::string> to_build;
    for (std::size_t i = 0; i < steps_.size(); ++i) {
      if (std::find(cached.begin(), cached.end(), i) != cached.end()) continue;
      if (!c_.plan.needed(steps_[i].position)) {
        skip(i);
        continue;
      }
      launched_.push_back(i);
      to_build.push_back(slot_[i]);
      c_.say("  building " + short_hash(steps_[i].commit) +
             (steps_[i].version.empty() ? "" : " (" + steps_[i].version + ")") + " in " + slot_[i]);
    }
    if (!to_build.empty()) builds_.start(to_build, index_ + 1);
    double last_end = 0;
    while (const auto end = builds_.wait_next()) {
      last_end = std::max(last_end, end->seconds);
      finish(launched_[end->index], end->ok, end->error, end->seconds);
      for (std::size_t j = 0; j < launched_.size(); ++j)
        if (!done_.count(launched_[j]) && !c_.plan.needed(steps_[launched_[j]].position)) {
          builds_.cancel(j);
          skip(launched_[j]);
        }
    }
    BisectRound& r = c_.result.rounds[index_];
    r.build_wall_s = last_end;
    r.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    r.finished = true;
    c_.save();
  }

 private:
  builds::SourceBuildOptions options(std::size_t i) const {
    builds::SourceBuildOptions b = c_.o.build;
    b.source = slot_[i];
    b.ref.clear();
    return b;
  }

  // A build of the round no longer needed: another result resolved its range.
  void skip(std::size_t i) {
    done_.insert(i);
    c_.result.rounds[index_].cancelled.push_back(steps_[i].commit);
    c_.say("  cancelled " + short_hash(steps_[i].commit) +
           ": the round's other results resolved its range");
    c_.save();
  }

  // Build `i` ended (or was in the cache): drawn, decided, recorded.
  void finish(std::size_t i, bool ok, const std::string& error, double seconds) {
    done_.insert(i);
    BisectStep& s = steps_[i];
    s.build_s = seconds;
    std::optional<builds::SourceBuildResult> build;
    if (ok) build = builds::cached_source_build(options(i));
    if (!ok) {
      s.error = "build failed: " + error;
    } else if (!build) {
      s.error = "build failed: the build cache does not hold the build of " + s.commit +
                " that `builds build` reported";
    } else {
      s.build = build->build.name;
      s.build_dir = build->build.dir;
      s.reused = seconds == 0;
      c_.say(s.reused ? "  reused build " + s.build
                      : "  built " + s.build + " in " + util::duration_text(seconds));
      draw_built_step(c_.o, c_.judged, s);
    }
    if (s.error.empty()) {
      c_.decide(s);
      c_.say("  drew " + short_hash(s.commit) + ": " + s.summary);
    } else {
      c_.plan.fail(s.position);
      c_.result.rounds[index_].failed.push_back(s.commit);
      c_.say("  skipped " + short_hash(s.commit) + " for every primitive: " + s.error);
    }
    c_.result.steps.push_back(s);
    c_.save();
  }

  RoundContext& c_;
  builds::BuildSlots& slots_;
  builds::CommitBuilds& builds_;
  std::size_t index_ = 0;
  std::vector<BisectStep> steps_;
  std::vector<std::string> slot_;
  std::vector<std::size_t> launched_;  // build index -> step index
  std::set<std::size_t> done_;
};

}  // namespace

void run_rounds(RoundContext& c) {
  builds::BuildSlots slots(c.o.source);
  const unsigned cores =
      c.o.build.jobs ? c.o.build.jobs : std::max(1u, std::thread::hardware_concurrency());
  // Declared after the slots: stopped before the slots are removed.
  const std::unique_ptr<builds::CommitBuilds> builds =
      c.o.slurm ? builds::slurm_commit_builds(c.o.build, c.o.jobs ? c.o.jobs : 2, c.o.slurm_options,
                                              slots.folder(), c.say)
                : builds::local_commit_builds(c.o.build, builds::jobs_per_build(cores, c.o.ways),
                                              slots.folder());
  for (;;) {
    util::throw_if_interrupted();
    const std::vector<std::size_t> positions = c.plan.next_k(c.o.ways);
    if (positions.empty()) break;
    Round(c, slots, *builds).run(positions);
  }
}

}  // namespace ra::triage
