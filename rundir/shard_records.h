// The seal rule, which every command that reads a run's records applies before it trusts a
// shard's file (analyze, report, audit, records, status, merge, show, reproduce, stats, run):
//   - a sealed file (rundir/shard_file.h) is trusted when its trailer matches its contents and
//     counts the shard's rows, and its first and last rows are the shard's first and last
//     primitives; a file cut at a frame boundary, two files run together, a changed byte,
//     appended text or another shard's file under this shard's name all fail it;
//   - a file without a seal is trusted only when it predates the seal: a plain CSV of records
//     schema version 2 holding each of the shard's primitives once. Every schema version 3 file
//     and every compressed file was written sealed, so one without its seal is damaged;
//   - <id>.csv and <id>.csv.zst both present is refused, naming both: which one holds the
//     shard's records is not for a reader to guess.
// A damaged file is never read for a verdict: readers stop with a UserError naming it (exit 2),
// `analyze` counts it as a damaged shard, `run` sets it aside and redoes the shard.
#pragma once

#include <string>

#include "rundir/shard.h"
#include "rundir/shard_file.h"

namespace ra::rundir {

// Why the records file at `path` may not be trusted as shard `s`'s records; "" when it may.
std::string shard_records_damage(const std::string& path, const Shard& s);
// The same, judged from the seal a reader computed in its own pass over the file (analyze reads
// each file once): the file itself is read again only when it has no seal.
std::string shard_records_damage(const std::string& path, const Shard& s, const ShardSeal& seal);

// What a run directory holds for one shard.
struct ShardRecordsFile {
  std::string path;    // DIR/records/<id>.csv.zst or .csv; "" when there is neither
  std::string damage;  // why it may not be trusted; "" when it may, or when the seal was not checked
};
// Finds shard `s`'s records file in `run_dir` and, unless `check_seal` is false, judges it. Throws
// util::UserError naming both files when <id>.csv and <id>.csv.zst are both there.
ShardRecordsFile find_shard_records(const std::string& run_dir, const Shard& s,
                                    bool check_seal = true);

// The records file of shard `s` for a reader that will use its rows: "" when the shard has none;
// throws util::UserError "PATH: damaged: WHY; ..." when it fails the seal rule (and as
// find_shard_records does).
std::string trusted_records_path(const std::string& run_dir, const Shard& s);

}  // namespace ra::rundir
