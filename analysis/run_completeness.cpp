#include "analysis/run_completeness.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>

#include "metrics/records.h"
#include "rundir/records_format.h"
#include "rundir/records_reader.h"
#include "rundir/experiment.h"
#include "rundir/manifest.h"
#include "rundir/run_experiment.h"
#include "rundir/run_folder.h"
#include "rundir/shard.h"
#include "rundir/shard_file.h"
#include "rundir/shard_records.h"
#include "rundir/slicing.h"
#include "util/atomic_file.h"
#include "util/dir_lock.h"
#include "util/parallel.h"
#include "util/zstd_stream.h"

namespace fs = std::filesystem;

namespace ra::analysis {
namespace {

std::string range(const rundir::Shard& s) {
  return "primitives " + std::to_string(s.begin) + "-" + std::to_string(s.end - 1);
}

}  // namespace

std::string RunCompleteness::one_line() const {
  if (!has_plan) return "completeness unknown: no experiment.toml, so no plan to compare with";
  std::string h = complete() ? "complete: " : "INCOMPLETE: ";
  if (is_slice() && shards_of_other_slices > 0)
    h = "a slice (" + std::to_string(slice_index) + " of " + std::to_string(slice_count) +
        ", one machine's share; " + std::to_string(shards_of_other_slices) +
        " shards belong to the other slices): ";
  h += std::to_string(shards_whole) + " of " + std::to_string(shards_planned) + " shards, " +
       std::to_string(primitives_present) + " of " + std::to_string(primitives_planned) +
       " primitives";
  if (!platforms_run.empty()) {
    std::string list;
    for (const std::string& p : platforms_run) list += (list.empty() ? "" : ", ") + p;
    h += " of the platforms run (--platform " + list + "; the " +
         std::to_string(shards_of_other_platforms) + " shards of the others were not asked for)";
  }
  if (!writer.empty()) h += "; being written now by " + writer;
  if (!problems.empty())
    h += "; " + std::to_string(problems.size()) + " problem" + (problems.size() > 1 ? "s" : "");
  if (!manifest_status.empty()) h += " (manifest: " + manifest_status + ")";
  return h;
}

std::string RunCompleteness::markdown(std::size_t max_listed) const {
  std::string md = "**Run " + one_line() + ".**\n";
  if (!problems.empty()) {
    md += "\n";
    for (std::size_t i = 0; i < problems.size() && i < max_listed; ++i) md += "- " + problems[i] + "\n";
    if (problems.size() > max_listed)
      md += "- ... and " + std::to_string(problems.size() - max_listed) + " more\n";
  }
  return md;
}

std::string RunCompleteness::remedy(const std::string& command) const {
  if (is_slice())
    return "Join the " + std::to_string(slice_count) + " slices with `renderaudit merge SLICE_DIR_1 "
           "... SLICE_DIR_" + std::to_string(slice_count) + " --out DIR` and " + command +
           " DIR, or pass --allow-incomplete to " + command + " this slice alone.";
  return "Finish the run (the same `renderaudit run` command), or pass --allow-incomplete to " +
         command + " it as it is.";
}

RunCompleteness check_run_completeness(const std::string& run_dir, const ShardSeals* seals) {
  RunCompleteness c;
  const std::string toml = rundir::run_folder::experiment(run_dir);
  if (!fs::exists(toml)) return c;
  c.has_plan = true;
  const rundir::Experiment exp = rundir::load_experiment(toml);
  c.writer = util::DirLock::current_holder(run_dir);
  std::optional<rundir::RunManifest> manifest;
  try {
    manifest = rundir::read_manifest_file(rundir::run_folder::manifest(run_dir));
  } catch (const std::exception& e) {
    // The reader's own words: the file and the key that is wrong, as status, audit and merge say.
    c.problems.push_back(e.what());
  }
  if (manifest) {
    // the copy is the records' experiment only while the manifest's hash is its own (exit 2)
    rundir::require_unchanged_experiment(exp, *manifest, run_dir);
    const rundir::RunManifest& m = *manifest;
    c.manifest_status = m.status;
    if (m.slice) c.slice_index = m.slice->index, c.slice_count = m.slice->count;
    if (m.platforms_run) c.platforms_run = *m.platforms_run;
  }
  if (c.manifest_status == "running" && c.writer.empty())
    c.problems.push_back("the manifest says \"running\" but nobody is writing: the run was killed "
                         "(run the same command again to finish it)");

  std::set<std::string> planned_files;
  std::vector<rundir::Shard>
      plan;  // the platforms run (all without --platform), as `status` plans it
  for (rundir::Shard& s : plan_shards(exp)) {
    // any platform's, in both formats (a shard with both files is a damaged shard, not a stray)
    for (const rundir::RecordsFormat f :
         {rundir::RecordsFormat::kCsv, rundir::RecordsFormat::kCsvZst})
      planned_files.insert(s.id() + rundir::records_extension(f));
    if (c.platforms_run.empty() || std::find(c.platforms_run.begin(), c.platforms_run.end(),
                                             s.platform) != c.platforms_run.end())
      plan.push_back(std::move(s));
    else
      ++c.shards_of_other_platforms;
  }
  std::set<std::string> own;  // a slice's own shards (ids); empty for a whole run
  if (c.is_slice())
    for (const rundir::Shard& s :
         shards_of_slice(plan, exp, rundir::Slice{c.slice_index, c.slice_count}))
      own.insert(s.id());
  // Each shard file is read whole (its seal's hash; decompressed when compressed): the files are
  // checked on every core, then counted in plan order.
  std::vector<std::string> verdicts(plan.size());
  std::vector<char> present(plan.size(), 0);
  util::run_in_parallel(plan.size(), 0, [&](std::size_t i) {
    const rundir::Shard& s = plan[i];
    rundir::ShardRecordsFile file;
    try {
      file = rundir::find_shard_records(run_dir, s, false);
    } catch (const util::UserError& e) {  // <id>.csv and <id>.csv.zst both there
      present[i] = 1;
      verdicts[i] = e.what();
      return;
    }
    if (file.path.empty()) return;
    present[i] = 1;
    const auto known = seals ? seals->find(fs::path(file.path).filename().string())
                             : ShardSeals::const_iterator();
    verdicts[i] = seals && known != seals->end()
                      ? rundir::shard_records_damage(file.path, s, known->second)
                      : rundir::shard_records_damage(file.path, s);
  });
  for (std::size_t i = 0; i < plan.size(); ++i) {
    const rundir::Shard& s = plan[i];
    ++c.shards_planned;
    c.primitives_planned += s.size();
    if (c.is_slice() && !own.count(s.id()) && !present[i]) {
      ++c.shards_of_other_slices;
      continue;
    }
    if (!present[i]) {
      c.problems.push_back("missing shard " + s.id() + " (" + range(s) + ")");
      continue;
    }
    if (!verdicts[i].empty()) {
      c.problems.push_back("damaged shard " + s.id() + ": " + verdicts[i]);
      continue;
    }
    ++c.shards_whole;
    c.primitives_present += s.size();
  }
  std::error_code ec;
  std::vector<std::string> stray;
  for (const auto& e : fs::directory_iterator(rundir::run_folder::records(run_dir), ec))
    if (rundir::is_records_file_name(e.path().filename().string()) &&
        !planned_files.count(e.path().filename().string()))
      stray.push_back(e.path().filename().string());
  std::sort(stray.begin(), stray.end());
  for (const std::string& f : stray)
    c.problems.push_back("records/" + f + " is not a shard of this experiment's plan (another "
                         "shard_size?): its records would be counted twice");
  return c;
}

}  // namespace ra::analysis
