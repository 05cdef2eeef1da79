// The primitives a run directory's records hold as `crash` or `timeout`, read from the records
// themselves: what the directory holds, whichever invocation, slice or merge wrote it. The
// manifest's `failed_primitives`, its status and the exit codes of `run` and `merge` follow it, so
// a re-run, a second merge or a gather never hides a failure an earlier one recorded.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rundir/manifest.h"
#include "rundir/shard.h"
#include "runner/shard_recovery.h"

namespace ra::runner {

// The crash and timeout records of `shards`' files in DIR/records (shards without a file are
// skipped), in shard order then index order; `reason` is taken from `reasons` (key: shard id and
// index, see failure_key), or says only that the records hold it. Reads every file once, line by
// line: memory does not depend on the run's size.
std::vector<FailedPrimitive> failed_primitives_in_records(
    const std::string& dir, const std::vector<rundir::Shard>& shards,
    const std::map<std::string, std::string>& reasons = {});

// "SHARD#INDEX": the key of `reasons`.
std::string failure_key(const std::string& shard, uint64_t index);

// Adds the reasons `manifest`'s `failed_primitives` list gives, by failure_key.
void add_failure_reasons(const rundir::RunManifest& manifest, std::map<std::string, std::string>* reasons);

}  // namespace ra::runner
