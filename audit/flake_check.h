// The flake check: "a difference that disappears when the primitive is rendered again is a flake".
// Every changed primitive (up to a cap) is rendered once more before the verdict, in child
// processes (`renderaudit worker TMPDIR PLATFORM KIND VIEW BEGIN END`, the same program and shard
// code `run` uses, so a driver that crashes or hangs takes down only its child), with
// RA_RENDER_ATTEMPT=2 in the child's environment (the attempt number of the coordinator's re-runs;
// the `faulty` test platform's flaky primitives are wrong on attempt 1 only). TMPDIR holds a copy
// of the run's experiment.toml; the worker writes TMPDIR/records/<shard id>.csv, read back here
// through its pixel_hash column, and TMPDIR is removed afterwards.
//
// Batching: the changed indices of one platform, kind and view are cut into index ranges, one child
// each; neighbours closer than `max_gap` (500) share a range: starting a child costs 0.3 to 1.5 s
// (the program loads its libraries; the driver compiles its shaders), about what a few hundred primitives
// cost to draw, so the unchanged ones in between are rendered too and ignored. A range never spans
// a primitive known to crash or hang (a crash/timeout record or a missing shard), so the check
// cannot trip over a known failure. Up to `jobs` children run at once.
//
// The decision (apply_flake_check):
// - run against baseline: only the current side is rendered again (the baseline's driver may no
//   longer exist); a flake when the re-render's pixels equal the baseline's.
// - `--between P1 P2` (two platforms of one run, both available here): both sides are rendered
//   again; a flake when the two re-renders have the same pixels, i.e. the difference vanished.
//
// One driver per record: the children load each platform's build (PLATFORM@BUILD) from the run's
// experiment, whatever this process's environment, and check GL_RENDERER and GL_VERSION against
// the run's driver files (copied into TMPDIR/drivers). A child that loaded another driver makes
// apply_flake_check throw UserError naming both: the audit stops (exit 2) rather than call a real
// change a flake.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "audit/audit_compare.h"
#include "audit/run_identity.h"

namespace ra::audit {

// One primitive to render again.
struct RerenderRequest {
  std::string platform;
  geometry::Kind kind = geometry::Kind::kPoint;
  int view = 0;
  uint64_t index = 0;
};

// Indices the batcher must not include in a range: (platform, kind, view) -> sorted indices and
// [begin, end) ranges known to crash or hang.
struct KnownFailures {
  std::map<std::tuple<std::string, int, int>, std::vector<std::pair<uint64_t, uint64_t>>> ranges;
  void add(const std::string& platform, geometry::Kind kind, int view, uint64_t begin,
           uint64_t end);
  bool hits(const std::string& platform, geometry::Kind kind, int view, uint64_t begin,
            uint64_t end) const;
};

struct RerenderOptions {
  std::string run_dir;     // whose experiment.toml is copied
  std::string program;     // runs `worker`; empty: util/worker_program.h
  unsigned jobs = 0;       // children at once; 0: the number of cores
  double timeout_s = 0;    // per child; 0: the experiment's run.shard_timeout_s
  uint64_t max_gap = 500;  // neighbours less than this far apart share a child
  int attempt = 2;         // RA_RENDER_ATTEMPT given to the children
  std::string experiment_text;  // non-empty: drawn with this experiment instead of the run's
                                // (a bisection declares each step's build in it)
  bool copy_driver_files = true;  // the run's drivers/*.json checked by the children
};

// A range rendered by one child.
struct RerenderBatch {
  std::string platform;
  geometry::Kind kind = geometry::Kind::kPoint;
  int view = 0;
  uint64_t begin = 0, end = 0;  // [begin, end)
  std::string error;            // empty when it succeeded; "crashed (signal 11)", "timed out ..."
};

struct RerenderResult {
  // (platform, kind, view, index) -> pixel_hash of the re-render, for every primitive rendered
  std::map<std::tuple<std::string, int, int, uint64_t>, uint64_t> hashes;
  std::map<std::tuple<std::string, int, int, uint64_t>, int64_t> pixels;  // lit pixels, same keys
  std::vector<RerenderBatch> batches;
  double seconds = 0;  // wall time of all children
};

// The ranges `requests` are cut into (see Batching above), sorted by platform, kind, view, begin.
std::vector<RerenderBatch> plan_rerender(std::vector<RerenderRequest> requests,
                                         const KnownFailures& avoid, uint64_t max_gap);

// Renders every batch in child processes. Throws std::runtime_error only when the temporary
// directory cannot be made; a child's failure is recorded in its batch.
RerenderResult rerender(const std::vector<RerenderBatch>& batches, const RerenderOptions& options);

struct FlakeCheckSummary {
  bool performed = false;       // false: --max-rerenders 0
  bool both_sides = false;      // --between: both platforms rendered again
  std::size_t cap = 0;          // at most this many changed primitives are checked
  std::size_t checked = 0;      // changed primitives rendered again
  std::size_t not_checked = 0;  // over the cap
  std::size_t flakes = 0, still_different = 0, rerender_failed = 0;
  std::size_t processes = 0;  // children started
  double seconds = 0;
  std::vector<RerenderBatch> failed_batches;  // children that crashed or timed out
};

// Re-renders comparison.changed (the first `cap` in their order) and sets each one's recheck.
// `between`: both sides are platforms of `current` (see the decision above).
FlakeCheckSummary apply_flake_check(audit::PrimitiveComparison& comparison,
                                    const std::vector<audit::PlatformPair>& pairs, bool between,
                                    const KnownFailures& avoid, std::size_t cap,
                                    const RerenderOptions& options);

}  // namespace ra::audit
