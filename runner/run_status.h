// `renderaudit status DIR`: where a run stands, read from its directory without taking its lock:
// shards done, running, failed and waiting, the writers at work (DIR itself, or the slices of a
// Slurm run under DIR/slices/) with their time left, and the Slurm jobs when there are some.
#pragma once

#include <string>
#include <vector>

#include "runner/run_progress.h"

namespace ra::runner {

struct WriterStatus {
  std::string dir;          // DIR or DIR/slices/K
  std::string holder;       // who holds its lock ("process P (run) on host H since T")
  RunProgress progress;     // its progress.json
};

struct SlurmJobStatus {
  std::string id;           // "12_3" for an array task, "13" for the gather
  std::string state;        // PENDING, RUNNING, ... as squeue says
  std::string reason;       // squeue's reason (Dependency, Resources, ...)
};

struct RunStatus {
  std::string dir, experiment;
  size_t planned = 0, done = 0, running = 0, failed = 0, waiting = 0;
  // "FILE: why" for each records file the seal rule rejects (rundir/shard_records.h); its shard
  // is counted neither done nor waiting
  std::vector<std::string> damaged;
  bool seals_checked = true;  // false: `status --quick`, files counted by their presence
  std::string manifest_status;  // DIR/manifest.json's "status", or "" when none yet
  std::vector<WriterStatus> writers;  // only those whose lock is held
  // Slurm (DIR/slurm/jobs.json present)
  bool slurm = false;
  std::string array_job, gather_job;
  int slices = 0;
  std::vector<SlurmJobStatus> jobs;   // what squeue still lists
  std::string squeue_error;           // why squeue could not be asked, or ""
  int gather_exit = -1;               // DIR/slurm/gather.exit, or -1
  double left_s = -1;                 // the longest writer's estimate; -1 unknown
  size_t slices_not_started = 0;      // Slurm tasks still pending
  int slice_index = 0, slice_count = 0;  // a `run --slice K/N` directory (its shards only); 0: not

  // "complete", "running", "queued", "damaged" (a records file fails the seal rule), "failed",
  // "interrupted", "incomplete", or "unknown" (a
  // Slurm run whose scheduler could not be asked, its gather not ended)
  std::string state() const;
};

// Throws ra::util::UserError when DIR is not a run directory. `check_seals` false: count a shard done
// when its file exists, without reading it (`status --quick`).
RunStatus read_run_status(const std::string& dir, const std::string& squeue = "squeue",
                          bool check_seals = true);

std::string format_run_status(const RunStatus& s);
nlohmann::json to_json(const RunStatus& s);

}  // namespace ra::runner
