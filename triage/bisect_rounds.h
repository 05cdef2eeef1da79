// The rounds of a bisection: the commits built together, the line each round prints, and the
// loop of `bisect --ways K` / `--slurm`.
//
// A round takes the K positions AttributionPlan::next_k chooses, checks each out in a slot
// (builds/build_slots.h: a git worktree of the source's own, so the tree itself is never moved),
// takes what the build cache holds already, and builds the rest at once (builds/commit_builds.h:
// here, ninja -j max(1, cores / K) each; or a Slurm job array, builds/slurm_builds.h). Each build
// is drawn as soon as it ends, and decided as a --ways 1 step is; a build whose range the
// round's results have resolved meanwhile is cancelled. Every step is saved as it is drawn, and
// the round's record with it, so an interrupted round resumes from the steps it finished; the
// slots are removed however the round ends.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "triage/bisect_types.h"
#include "triage/bisect_plan.h"

namespace ra::triage {

// What the rounds need of the bisection around them.
struct RoundContext {
  const BisectOptions& o;
  const std::vector<std::string>& line;          // position -> commit
  const std::vector<BisectPrimitive>& judged;    // what each step draws
  BisectResult& result;                          // steps and rounds appended
  AttributionPlan& plan;
  std::function<void(const std::string&)> say;
  std::function<void()> save;                    // bisect.json written
  std::function<void(BisectStep&)> decide;       // a drawn step's summary made, the plan told
};

// Round `result.rounds.size() + 1` begun over `positions` and recorded: the plan's state before it.
BisectRound& begin_round(RoundContext& c, const std::vector<std::size_t>& positions,
                         const std::string& where);

// "round R: K builds (HASHES), N changes unresolved, about M rounds to go"
std::string round_line(const BisectRound& r);

// "R rounds, B builds, T of building": the bisection's builds over every invocation.
std::string rounds_summary(const BisectResult& r);

// Rounds of o.ways builds until the plan is done. Throws util::Interrupted on a signal (the
// round's builds stopped and its slots removed first).
void run_rounds(RoundContext& c);

}  // namespace ra::triage
