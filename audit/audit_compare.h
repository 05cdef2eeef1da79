// Per-primitive comparison of two sides of an audit. Primitive i of a kind is the same primitive in
// both (a pure function of seed, kind and index: geometry/primitive.h), so its lit pixels are
// compared exactly, through the records' `pixel_hash` (FNV-1a 64 of the sorted lit pixels), with
// the case status and the visibility class. Nothing here depends on how the runner stores pixels.
//
// A side is a run directory and one of its platforms: a run against its baseline compares platform
// P of the baseline with platform P of the current run; `--between P1 P2` compares two platforms of
// one run (P1 plays the baseline). Records are read one platform x kind x view at a time (the
// shards its run's experiment.toml plans), so memory stays that of one view whatever the run's
// size.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/primitive.h"
#include "metrics/records.h"

namespace ra::audit {

// The platforms compared: `baseline` of the baseline side against `current` of the current side.
struct PlatformPair {
  std::string baseline, current;
  // "osmesa-llvmpipe" when both are the same platform, else "P1 vs P2".
  std::string label() const;
};

// The metric shown beside each changed primitive: pe (points, px), lse_u (lines, px), te_u
// (triangles, px^2): the paper's unsigned error of the kind, in pixel units.
const char* headline_metric(geometry::Kind kind);

// What one side's record says about a primitive (units as in the records).
struct PrimitiveState {
  metrics::CaseStatus status = metrics::CaseStatus::kOk;
  metrics::Visibility visibility = metrics::Visibility::kTrueInvisible;
  int64_t pixels = 0;       // lit pixels
  uint64_t pixel_hash = 0;  // FNV-1a 64 of the sorted lit pixels
  double metric = metrics::kNA;  // headline_metric(kind); NaN when not applicable
  int64_t ref_diff = -1;    // pixels differing from the reference rasterizer; -1: not measured
  metrics::Conformance conformance =
      metrics::Conformance::kNotCompared;  // the GL verdict (metrics/conformance.h)
  int64_t violating_pixels = -1;
};

// True when `c` is a violation its baseline did not have: the current side violates a GL rule
// and the baseline's record of the primitive did not (another class, or no verdict at all).
bool new_violation(const struct ChangedPrimitive& c);

// What re-rendering a changed primitive showed (audit/flake_check.h).
enum class Recheck {
  kNotRerendered,   // over the re-render cap, or the flake check was off: counted as changed
  kStillDifferent,  // the re-render differs too: a real change
  kFlake,           // the difference disappeared on re-render: a flake, not a change
  kRerenderFailed,  // the re-render crashed or timed out: counted as changed (and as a failure)
};
const char* recheck_name(Recheck r);  // "not re-rendered", "still different", "flake", ...

struct ChangedPrimitive {
  std::size_t pair = 0;  // index into the audit's PlatformPair list
  geometry::Kind kind = geometry::Kind::kPoint;
  int view = 0, view_group = 0;  // view 1-based; view_group 0 = A
  uint64_t index = 0;
  PrimitiveState before, after;  // baseline side, current side
  Recheck recheck = Recheck::kNotRerendered;
  uint64_t rerender_hash = 0;  // pixel_hash of the current side's re-render (when re-rendered)
};

// A record whose status is crash or timeout: the primitive took its worker down.
struct FailedPrimitive {
  std::size_t pair = 0;
  std::string side;      // "baseline" or "current"
  std::string platform;  // the side's platform
  geometry::Kind kind = geometry::Kind::kPoint;
  int view = 0, view_group = 0;
  uint64_t index = 0;
  metrics::CaseStatus status = metrics::CaseStatus::kCrash;
};

// Counts of one pair, kind and view.
struct ViewCounts {
  std::size_t pair = 0;
  geometry::Kind kind = geometry::Kind::kPoint;
  int view = 0, view_group = 0;
  uint64_t compared = 0;   // primitives with a record on both sides
  uint64_t changed = 0;    // compared, pixels / status / visibility differ (flakes included)
  uint64_t failed = 0;     // crash or timeout on either side
  uint64_t unmatched = 0;  // a record on one side only (the other side's shard is missing)
};

struct PrimitiveComparison {
  std::vector<ViewCounts> views;          // by pair, kind, view
  std::vector<ChangedPrimitive> changed;  // by pair, kind, view, index
  std::vector<FailedPrimitive> failed;    // by pair, kind, view, index, side
};

// Compares every primitive of every pair. Each side's shards are those its run's experiment plans
// (same primitives, perhaps another shard size); absent records files count as unmatched here and
// are reported as missing shards by audit/run_identity.h. `jobs` threads read views in parallel
// (0: the number of cores). `compare_verdicts` false: the runs were judged by different
// conformance rules (RunIdentity::conformance_rules), so a class change alone is no change.
// Throws ra::util::UserError on a malformed records file.
PrimitiveComparison compare_primitives(const std::string& baseline_dir,
                                       const std::string& current_dir,
                                       const std::vector<PlatformPair>& pairs, unsigned jobs = 0,
                                       bool compare_verdicts = true);

// True when two records of one primitive differ: status, visibility, lit pixels, or the
// conformance class (when both records have one: a baseline of schema version 2 has none).
bool states_differ(const PrimitiveState& a, const PrimitiveState& b);

}  // namespace ra::audit
