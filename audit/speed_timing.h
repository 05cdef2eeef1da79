// Drawing time measured to be compared: two or more sides (platforms, each drawn with its own
// run's experiment and driver build) draw the same primitives, one process at a time, their
// processes interleaved in rounds, so that the machine's drift and load fall on every side alike.
//
// - Each round starts a fresh process per side (`serve-shards DIR PLATFORM --alone`, the worker
//   `run` uses), which draws every primitive of the sample alone (a batch of one): its render_us
//   is the primitive's own time on the platform's clock, never a batch's mean, so it means the
//   same on every side whatever pixels the sides draw (docs/records.md, "Comparing drawing
//   time"). Each process first draws the whole sample once untimed: the first pass pays for the
//   driver compiling code for each new state.
// - Then the sides take turns range by range (one kind and view: milliseconds of drawing), one
//   process drawing at a time while the others wait for their next command, the order of the
//   sides reversed from one range to the next (ABC, CBA, ...): a change of the machine's load
//   slower than a few ranges falls on every side alike, and over two ranges every side has the
//   same mean position.
// - Fresh processes every round: what stays with a process for its life (the core it runs on,
//   where its memory landed) differs from round to round, so the rounds are the replicates
//   (audit/speed_audit.h).
// - The children load each side's platform (PLATFORM@BUILD) from the side's experiment and check
//   GL_RENDERER and GL_VERSION against the side's run's driver files, as the flake check's do
//   (audit/flake_check.h): a side whose driver is no longer what made its run fails with the
//   child's words in SideTiming::error rather than time another driver.
// Times are microseconds, as render_us.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "geometry/primitive.h"

namespace ra::audit {

// One side: a platform drawn with a run's experiment and driver files.
struct TimingSide {
  std::string label;            // "baseline", "current", "control": for messages
  std::string platform;         // drawn by the children, e.g. "egl-llvmpipe@backports"
  std::string run_dir;          // its experiment.toml (unless experiment_text) and drivers/*.json
  std::string experiment_text;  // non-empty: drawn with this experiment instead of the run's
  bool check_driver = true;     // the run's drivers/*.json checked by the children
};

// Primitives [begin, end) of one kind and view, under the sides' common seed.
struct TimingRange {
  geometry::Kind kind = geometry::Kind::kPoint;
  int view = 0;  // 1-based
  uint64_t begin = 0, end = 0;
};

struct TimingOptions {
  int repeats = 10;       // rounds: each side drawn this many times, each in a fresh process
  std::string program;    // runs `serve-shards`; empty: util/worker_program.h
  double timeout_s = 0;   // per process; 0: the first side's experiment's run.shard_timeout_s
};

// (kind, view, index)
using TimedKey = std::tuple<int, int, uint64_t>;

// Times of one side for a set of primitives: element [i][r] is primitive i's time in round r
// (microseconds, > 0), the same number of rounds for every primitive.
using RoundTimes = std::vector<std::vector<double>>;

struct SideTiming {
  // render_us of each round in which the primitive was drawn (rounds in order)
  std::map<TimedKey, std::vector<double>> render_us;
  std::string error;   // non-empty: a process of this side failed (its last words)
  double seconds = 0;  // wall time of this side's processes, all rounds
};

struct TimingResult {
  std::vector<SideTiming> sides;               // as given
  std::vector<std::vector<std::size_t>> order;  // per round, the order of its first range
  double seconds = 0;                          // wall time of everything
};

// Per side, the times of those `keys` that every side drew in every one of `rounds` rounds with a
// positive time (a platform that does not time its drawing gives 0): element [side][i][r], the
// same primitives in the same order on every side.
std::vector<RoundTimes> common_round_times(const std::vector<const SideTiming*>& sides,
                                           const std::vector<TimedKey>& keys, int rounds);

// `more`'s rounds appended to `into`'s, primitive by primitive (a repeat of the same timing).
void append_rounds(SideTiming& into, const SideTiming& more);

// The order of the sides for turn `turn` (0-based): forward when even, reversed when odd.
std::vector<std::size_t> round_order(std::size_t sides, int turn);

// Draws every range on every side, `options.repeats` rounds. A side whose process fails is not
// drawn again (its error says why); the others go on. Throws std::runtime_error only when a
// temporary folder cannot be made; util::UserError for a side's experiment that does not parse.
// `progress` (may be empty) is told after each round: the round, sides.size(), its seconds.
TimingResult time_interleaved(
    const std::vector<TimingSide>& sides, const std::vector<TimingRange>& ranges,
    const TimingOptions& options,
    const std::function<void(int round, std::size_t side, double seconds)>& progress = {});

}  // namespace ra::audit
