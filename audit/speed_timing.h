// Drawing time measured to be compared: two or more sides (platforms, each drawn with its own
// run's experiment and driver build) draw the same primitives, one process at a time, their
// processes interleaved in rounds, so that the machine's drift and load fall on every side alike.
//
// - Each side of each round is one fresh process (`serve-shards DIR PLATFORM --alone`, the worker
//   `run` uses), drawing every primitive of the sample alone (a batch of one): its render_us is
//   the primitive's own time on the platform's clock, never a batch's mean, so it means the same
//   on every side whatever pixels the sides draw (docs/records.md, "Comparing drawing time").
//   It draws the sample twice and keeps the second pass: the first pays for the driver compiling
//   its code for each new state.
// - No two processes draw at once: a side never shares the cores with another side.
// - Round r draws the sides in order 0, 1, ..., k-1 when r is even and in reverse when it is odd
//   (ABC, CBA, ...): over two rounds every side has the same mean position, so a drift linear in
//   time adds the same to each side. An odd number of rounds leaves the first and last sides one
//   position apart; the default is even.
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
  int repeats = 4;        // rounds: each side drawn this many times, each in a fresh process
  std::string program;    // runs `serve-shards`; empty: util/worker_program.h
  double timeout_s = 0;   // per process; 0: the first side's experiment's run.shard_timeout_s
};

// (kind, view, index)
using TimedKey = std::tuple<int, int, uint64_t>;

struct SideTiming {
  // render_us of each round in which the primitive was drawn (rounds in order), and its pixels
  std::map<TimedKey, std::vector<double>> render_us;
  std::map<TimedKey, uint64_t> pixel_hash;
  std::string error;   // non-empty: a process of this side failed (its last words)
  double seconds = 0;  // wall time of this side's processes, all rounds
};

struct TimingResult {
  std::vector<SideTiming> sides;               // as given
  std::vector<std::vector<std::size_t>> order;  // per round, the sides in the order drawn
  double seconds = 0;                          // wall time of everything
};

// The order of round `round` (0-based) over `sides` sides.
std::vector<std::size_t> round_order(std::size_t sides, int round);

// Draws every range on every side, `options.repeats` rounds. A side whose process fails is not
// drawn again (its error says why); the others go on. Throws std::runtime_error only when a
// temporary folder cannot be made; util::UserError for a side's experiment that does not parse.
// `progress` (may be empty) is told after each process: round, side, seconds it took.
TimingResult time_interleaved(
    const std::vector<TimingSide>& sides, const std::vector<TimingRange>& ranges,
    const TimingOptions& options,
    const std::function<void(int round, std::size_t side, double seconds)>& progress = {});

}  // namespace ra::audit
