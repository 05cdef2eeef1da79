// The seal rule every reader of records applies (see the header).
#include "rundir/shard_records.h"

#include <unistd.h>

#include <vector>

#include "metrics/records.h"
#include "rundir/records_reader.h"
#include "util/errors.h"
#include "util/zstd_stream.h"

namespace ra::rundir {
namespace {

bool exists(const std::string& path) { return ::access(path.c_str(), F_OK) == 0; }

std::string primitive_range(const Shard& s) {
  return "primitives " + std::to_string(s.begin) + "-" + std::to_string(s.end - 1);
}

// A file without a seal (`no_seal` says so). The seal came during records schema version 2, so
// every file of version 3 or later was written sealed: one without its seal is damaged (cut
// short, or edited). A version 2 file may predate the seal: it is checked row by row instead.
// Empty when it holds each of the shard's primitives exactly once and nothing else.
std::string check_unsealed(const std::string& path, const Shard& s, const std::string& no_seal) {
  const int version = rundir::records_schema_version(path);
  // A compressed file cut inside its first frame shows no header at all; compression came after
  // the seal, so such a file was written sealed and is simply cut short.
  if (version == 0 && util::has_zstd_extension(path)) return no_seal;
  if (version >= 3)
    return no_seal + "; records of schema version " + std::to_string(version) +
           " are always written sealed, so this file is damaged";
  if (version != 2) return "unexpected header";
  std::vector<bool> seen(s.size(), false);
  uint64_t rows = 0;
  try {
    rundir::for_each_record_row(path, [&](const rundir::RecordRow& row) {
      const uint64_t index = row.integer<uint64_t>(metrics::RecordColumn::kIndex);
      if (index < s.begin || index >= s.end)
        row.fail("primitive " + std::to_string(index) + " lies outside the shard (" +
                 primitive_range(s) + ")");
      if (seen[index - s.begin]) row.fail("primitive " + std::to_string(index) + " twice");
      seen[index - s.begin] = true;
      ++rows;
    });
  } catch (const util::UserError& e) {
    // "PATH:LINE: why" -> "line LINE: why" (the caller names the file)
    const std::string what = e.what();
    return what.rfind(path + ":", 0) == 0 ? "line " + what.substr(path.size() + 1) : what;
  }
  if (rows != s.size())
    return std::to_string(rows) + " of the shard's " + std::to_string(s.size()) + " primitives";
  return "";
}

std::string judged(const std::string& path, const Shard& s, std::string why) {
  if (why.rfind("no trailer", 0) == 0) return check_unsealed(path, s, why);
  return why;
}

}  // namespace

std::string shard_records_damage(const std::string& path, const Shard& s) {
  return judged(path, s, check_shard_file(path, s));
}

std::string shard_records_damage(const std::string& path, const Shard& s, const ShardSeal& seal) {
  return judged(path, s, seal_verdict(seal, s, util::has_zstd_extension(path)));
}

ShardRecordsFile find_shard_records(const std::string& run_dir, const Shard& s, bool check_seal) {
  const std::string compressed = s.records_path(run_dir, rundir::RecordsFormat::kCsvZst);
  const std::string plain = s.records_path(run_dir, rundir::RecordsFormat::kCsv);
  const bool has_compressed = exists(compressed), has_plain = exists(plain);
  if (has_compressed && has_plain)
    throw util::UserError(
        plain + " and " + compressed + ": both hold records of shard " + s.id() +
        ", and which one to trust is not for a reader to guess; remove the one that is not the "
        "shard's records (a run resumed with another run.records_format writes the new format)");
  ShardRecordsFile f;
  if (!has_compressed && !has_plain) return f;
  f.path = has_compressed ? compressed : plain;
  if (check_seal) f.damage = shard_records_damage(f.path, s);
  return f;
}

std::string trusted_records_path(const std::string& run_dir, const Shard& s) {
  const ShardRecordsFile f = find_shard_records(run_dir, s);
  if (!f.damage.empty())
    throw util::UserError(f.path + ": damaged: " + f.damage +
                          "; nothing is concluded from a damaged records file. `renderaudit run` "
                          "of this directory redoes the shard (it keeps this file as " +
                          f.path + ".damaged, or .damaged.2, ... when that name is taken)");
  return f.path;
}

}  // namespace ra::rundir
