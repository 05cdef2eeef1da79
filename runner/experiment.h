// A declarative experiment: platforms x views x primitive counts, parsed from a TOML file and
// validated before anything renders. The file format is documented in README.md ("Experiment
// files"); experiments/quick.toml and experiments/nist2008.toml are complete examples.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "runner/primitive.h"
#include "runner/view.h"

namespace ra {

// Faults injected by the `faulty` test platform (the reference rasterizer plus failures), so the
// pipeline's own crash, hang and completeness handling can be tested. Indices apply to every kind
// and view.
struct FaultPlan {
  std::string base = "reference";    // the platform that draws: "reference" or an OSMesa platform
  std::vector<uint64_t> crash;       // the worker aborts on these primitive indices
  std::vector<uint64_t> hang;        // the worker sleeps forever on these
  std::vector<uint64_t> wild_pixel;  // one extra pixel lit far from the primitive
  double shift_fraction = 0;         // this fraction of primitives is drawn one pixel to the right
  double flaky_fraction = 0;         // ... shifted only on the first attempt (RA_RENDER_ATTEMPT < 2)
};

struct Experiment {
  std::string path;        // the file as given
  std::string name;        // `name` key, default the file's stem; names outputs/<name>/
  std::string text;        // the file's bytes
  std::string hash;        // hex FNV-1a 64 of the canonical TOML, [run] excluded
  uint64_t seed = 0;
  std::vector<std::string> platforms;
  std::vector<View> views;             // cartesian product, numbered as in the paper's Table 1
  std::array<uint64_t, 3> counts{};    // primitives per view, indexed by Kind
  uint64_t shard_size = 5000;          // primitives per shard
  double shard_timeout_s = 600;        // a shard still running after this is killed
  FaultPlan faults;
};

// Limits checked by validation (also quoted in error messages).
constexpr int kMaxWindow = 16384;
constexpr uint64_t kMaxPrimitives = 100000000;  // per kind and view
constexpr int kMaxOrientations = 1000;

// Parses and validates; throws UserError "file:line:column: what (allowed: ...)".
Experiment load_experiment(const std::string& path);
Experiment parse_experiment(const std::string& text, const std::string& path);

}  // namespace ra
