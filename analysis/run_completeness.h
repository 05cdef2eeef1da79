// Is a run directory whole? Its records are compared with the plan its experiment.toml makes
// (rundir/shard.h): every planned shard must have a sealed records file (rundir/shard_file.h)
// holding exactly its primitives, no other records file may be there, and no writer may be at work.
// `analyze` and `report` check this first and stop (exit 3, kExitIncomplete) when it fails, unless
// told to go on (--allow-incomplete), in which case what is missing is written at the top of what
// they produce.
#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "rundir/shard_file.h"
#include "util/errors.h"

namespace ra::analysis {

struct RunCompleteness {
  bool has_plan = false;  // DIR/experiment.toml present (runs made by `run` always have it)
  uint64_t shards_planned = 0, shards_whole = 0;
  uint64_t primitives_planned = 0, primitives_present = 0;  // renders: platforms x views x counts
  std::string manifest_status;       // as manifest.json says ("complete", "running", ...), or ""
  std::string writer;                // who is writing the directory now, or ""
  std::vector<std::string> problems;  // one line each, e.g. "missing shard X (primitives 0-4999)"
  // A slice (`run --slice K/N`, manifest "slice"): one machine's share of the plan. Its own shards
  // are checked as above; the other slices' shards are counted, not listed, and the remedy is
  // `renderaudit merge`, not running it again.
  int slice_index = 0, slice_count = 0;  // 0: not a slice
  // A run of some platforms only (`run --platform P`, manifest "platforms_run"), as `status`
  // counts it: whole when their shards are; the other platforms' shards are not planned here.
  std::vector<std::string> platforms_run;  // empty: every platform of the experiment
  uint64_t shards_of_other_platforms = 0;
  uint64_t shards_of_other_slices = 0;   // planned shards that belong to the other slices

  bool is_slice() const { return slice_count > 0; }

  bool complete() const {
    return has_plan && problems.empty() && writer.empty() && shards_of_other_slices == 0;
  }
  // "complete: 16 of 16 shards, 64000 of 64000 primitives", or what is wrong, in one line.
  std::string one_line() const;
  // Markdown: that line and the problems (at most `max_listed`, then how many more).
  std::string markdown(std::size_t max_listed = 20) const;
  // What to do about it, one sentence for `command` ("analyze", "report"): finish the run, or for
  // a slice, merge the slices.
  std::string remedy(const std::string& command) const;
};

// Reads DIR/experiment.toml, DIR/manifest.json and DIR/records/ (every records file once, in
// blocks: memory does not depend on the run's size). Throws ra::util::UserError when the experiment file
// is unreadable. `seals`: the seals of records files already read (by file name, as
// load_run_records reads them), which are then judged without reading those files again.
using ShardSeals = std::map<std::string, rundir::ShardSeal>;  // by file name
RunCompleteness check_run_completeness(const std::string& run_dir,
                                       const ShardSeals* seals = nullptr);

// What analyze and report throw when the run is incomplete and going on was not allowed.
class IncompleteRunError : public util::UserError {
 public:
  explicit IncompleteRunError(const std::string& what) : util::UserError(what) {}
};

}  // namespace ra::analysis
