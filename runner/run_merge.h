// `renderaudit merge DIR_1 ... DIR_N --out DIR`: the slices of one run (`run --slice K/N` on N
// machines, or any run directories of the same experiment) gathered into one run directory that
// analyze, plot, report and audit cannot tell from a run made on one machine.
//
// Every planned shard is taken from the first input that holds it sealed and whole
// (rundir/shard_file.h) and copied atomically; a shard found in several inputs is taken once. The
// inputs must hold the same experiment (its hash), and each platform's driver must say the same
// GL_RENDERER and GL_VERSION and have loaded libraries of the same bytes (the fingerprints of
// drivers/P.json build.libraries) in every input, unless told otherwise (a run across two driver
// builds would compare nothing). The merged manifest records every input: its slice, host, invocations and
// driver strings. DIR is locked while it is written, and a merge over an earlier merge keeps the
// shards already there (it resumes).
#pragma once

#include <string>
#include <vector>

namespace ra::runner {

struct MergeOptions {
  std::vector<std::string> inputs;
  std::string out_dir;
  bool allow_driver_mismatch = false;
};

struct MergeResult {
  std::size_t shards_total = 0, shards_present = 0;  // planned; with a whole file in DIR now
  std::size_t shards_copied = 0;                     // by this merge
  std::size_t shards_in_several_inputs = 0;          // taken from the first of them
  std::vector<std::string> missing;                  // planned shards no input holds whole
  std::vector<std::string> damaged;                  // "FILE: why" of input files not taken
  std::size_t failed_primitives = 0;                 // crash and timeout records DIR holds
};

// Throws ra::util::UserError naming the input and what differs.
MergeResult merge_runs(const MergeOptions& options);

}  // namespace ra::runner
