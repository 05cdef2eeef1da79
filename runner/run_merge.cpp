// Gathering run directories of one experiment into one (see the header).
#include "runner/run_merge.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <nlohmann/json.hpp>

#include "metrics/conformance.h"
#include "rundir/experiment.h"
#include "rundir/manifest.h"
#include "rundir/run_folder.h"
#include "runner/recorded_failures.h"
#include "runner/prepare_run_dir.h"
#include "rundir/run_experiment.h"
#include "rundir/shard.h"
#include "rundir/shard_file.h"
#include "rundir/shard_records.h"
#include "util/atomic_file.h"
#include "util/errors.h"
#include "util/json_file.h"

namespace fs = std::filesystem;

namespace ra::runner {
namespace {

// platform -> its driver file, from DIR/drivers/*.json
std::map<std::string, nlohmann::json> drivers_of(const std::string& dir) {
  std::map<std::string, nlohmann::json> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(rundir::run_folder::drivers(dir), ec))
    if (e.path().extension() == ".json")
      out[e.path().stem().string()] = util::read_json_or_null(e.path().string());
  return out;
}

// A hard link where both are on one file system (a Slurm run's slices live under its directory:
// no second copy of the records), a copy otherwise. Either way the file appears whole or not at
// all; a slice re-run later replaces its own file by rename, never the linked one's contents.
void copy_atomically(const std::string& from, const std::string& to) {
  std::error_code ec;
  const std::string link_tmp = to + ".link.tmp";
  fs::remove(link_tmp, ec);
  fs::create_hard_link(from, link_tmp, ec);
  if (!ec) {
    fs::rename(link_tmp, to, ec);
    if (!ec) return;
    fs::remove(link_tmp, ec);
  }
  const std::string tmp = util::create_unique_temp(to);
  fs::copy_file(from, tmp, fs::copy_options::overwrite_existing, ec);
  if (ec) {
    fs::remove(tmp);
    throw std::runtime_error("cannot copy " + from + " to " + tmp + ": " + ec.message() +
                             util::free_space_note(to));
  }
  util::commit_file(tmp, to);
}

// The inputs' experiment, after checking they hold one experiment cut into one shard size.
rundir::Experiment common_experiment(const MergeOptions& options) {
  std::vector<rundir::Experiment> experiments;
  for (const std::string& in : options.inputs) {
    std::error_code ec;
    if (in == options.out_dir || fs::equivalent(in, options.out_dir, ec))
      throw util::UserError("merge: " + in + " is both an input and --out");
    if (!fs::exists(rundir::run_folder::experiment(in)))
      throw util::UserError("merge: " + in + ": not a run directory (no experiment.toml)");
    experiments.push_back(rundir::load_run_experiment(in));
    if (experiments.back().hash != experiments.front().hash) {
      throw util::UserError("merge: " + in + " holds experiment " + experiments.back().name +
                            " (hash " + experiments.back().hash + "), " + options.inputs.front() +
                            " holds " + experiments.front().name + " (hash " +
                            experiments.front().hash +
                            "): only slices of one experiment can be merged");
    }
  }
  const rundir::Experiment& exp = experiments.front();
  // [run] shard_size is outside the hash but names the records files: slices cut with another
  // size hold none of this plan's shards.
  for (std::size_t i = 1; i < experiments.size(); ++i)
    if (experiments[i].shard_size != exp.shard_size)
      throw util::UserError("merge: " + options.inputs[i] + " was cut into shards of " +
                            std::to_string(experiments[i].shard_size) +
                            " primitives ([run] shard_size), " + options.inputs.front() +
                            " into shards of " + std::to_string(exp.shard_size) +
                            ": their records files name other shards; run the slices with one "
                            "shard_size");
  return exp;
}

// platform -> library file name -> (fingerprint, the driver file that recorded it)
using LibrariesSeen = std::map<std::string, std::map<std::string, std::pair<std::string, std::string>>>;

// The driver file `path` (of `platform`, JSON `j`) against the libraries the inputs before it
// recorded (build.libraries: path and FNV-1a 64 of the bytes), matched by file name: GL strings
// alone cannot tell two builds of one Mesa version apart, and the merged directory keeps one driver
// file per platform, so slices drawn with other library bytes are refused, not merged under one.
void require_same_libraries(const std::string& path, const std::string& platform,
                            const nlohmann::json& j, LibrariesSeen* seen) {
  const auto build = j.find("build");
  if (build == j.end() || !build->is_object()) return;
  const auto libraries = build->find("libraries");
  if (libraries == build->end() || !libraries->is_array()) return;
  for (const nlohmann::json& l : *libraries) {
    if (!l.is_object() || !l.contains("path") || !l["path"].is_string() || !l.contains("fnv1a64") ||
        !l["fnv1a64"].is_string())
      throw util::UserError("merge: " + path + ": build.libraries: each entry needs a \"path\" "
                            "and an \"fnv1a64\" string");
    const std::string file = fs::path(l["path"].get<std::string>()).filename().string();
    const std::string fingerprint = l["fnv1a64"].get<std::string>();
    const auto [it, first] = (*seen)[platform].try_emplace(file, fingerprint, path);
    if (!first && it->second.first != fingerprint)
      throw util::UserError(
          "merge: platform " + platform + " drew with library " + file + " of fingerprint " +
          fingerprint + " (FNV-1a 64 of its bytes) in " + path + " but of fingerprint " +
          it->second.first + " in " + it->second.second +
          ": the same GL strings, other library bytes (another build, or a library rebuilt or "
          "patched between the slices), so their records are not one run's; run the slices "
          "again with one build (--allow-driver-mismatch merges them anyway, and the merged "
          "directory keeps the first input's driver file)");
  }
}

// Every platform an input holds records of must say which driver drew them, the same in every
// input (unless --allow-driver-mismatch).
void require_one_driver_per_platform(const MergeOptions& options, const std::vector<rundir::Shard>& plan) {
  if (!options.allow_driver_mismatch) {
    for (const std::string& in : options.inputs) {
      std::set<std::string> platforms;
      for (const rundir::Shard& s : plan)
        if (!platforms.count(s.platform) && !rundir::find_shard_records(in, s, false).path.empty())
          platforms.insert(s.platform);
      for (const std::string& platform : platforms)
        if (!fs::exists(rundir::run_folder::driver(in, platform)))
          throw util::UserError(
              "merge: " + in + " holds records of " + platform + " but no drivers/" + platform +
              ".json, so the driver that drew them cannot be compared "
              "with the other inputs' (--allow-driver-mismatch merges it anyway)");
    }
  }
  std::map<std::string, std::pair<std::string, std::string>> driver_seen;  // platform -> text, dir
  LibrariesSeen libraries_seen;
  for (const std::string& in : options.inputs) {
    for (const auto& [platform, j] : drivers_of(in)) {
      if (!j.is_object()) continue;
      const std::string text = j.value("renderer", "") + " | " + j.value("version", "");
      const auto [it, first] = driver_seen.try_emplace(platform, text, in);
      if (!first && it->second.first != text && !options.allow_driver_mismatch) {
        throw util::UserError("merge: platform " + platform + " drew with '" + text + "' in " + in +
                              " but with '" + it->second.first + "' in " + it->second.second +
                              " (--allow-driver-mismatch merges them anyway)");
      }
      if (!options.allow_driver_mismatch)
        require_same_libraries(rundir::run_folder::driver(in, platform), platform, j,
                               &libraries_seen);
    }
  }
}

// Copies every planned shard DIR lacks from the first input that holds it whole; returns how many
// shards were taken from each input.
std::map<std::string, uint64_t> copy_shards(const MergeOptions& options,
                                            const std::vector<rundir::Shard>& plan, MergeResult* result) {
  std::map<std::string, uint64_t> taken_from;
  for (const rundir::Shard& s : plan) {
    const rundir::ShardRecordsFile target = rundir::find_shard_records(options.out_dir, s);
    if (!target.path.empty() && target.damage.empty()) {
      ++result->shards_present;  // an earlier merge put it there
      continue;
    }
    int holders = 0;
    for (const std::string& in : options.inputs) {
      const rundir::ShardRecordsFile held = rundir::find_shard_records(in, s);  // the seal rule
      if (!held.damage.empty()) result->damaged.push_back(held.path + ": " + held.damage);
      if (held.path.empty() || !held.damage.empty()) continue;
      const std::string& source = held.path;
      if (++holders == 1) {
        copy_atomically(source, rundir::run_folder::records(options.out_dir) + "/" +
                                    fs::path(source).filename().string());
        ++result->shards_copied;
        ++result->shards_present;
        ++taken_from[in];
      }
    }
    if (holders > 1) ++result->shards_in_several_inputs;
    if (holders == 0) result->missing.push_back(s.id());
  }
  return taken_from;
}

// One version of the conformance rules for every input's records: that version (this
// renderaudit's when no input says).
int common_conformance_rules(const std::vector<rundir::RunManifest>& inputs, const MergeOptions& options) {
  int rules = 0;
  std::string rules_from;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const std::string path = rundir::run_folder::manifest(options.inputs[i]);
    const int r = inputs[i].rules_judged_by();
    if (r == 0) continue;
    if (rules != 0 && r != rules)
      throw util::UserError(rules_from + " was judged by conformance rules " +
                            std::to_string(rules) + ", " + path + " by " + std::to_string(r) +
                            ": their records cannot be merged");
    rules = r, rules_from = path;
  }
  return rules != 0 ? rules : metrics::kConformanceRulesVersion;
}

// An input as the merged manifest lists it: what was taken, its drivers, its own provenance.
rundir::ManifestInput input_entry(const std::string& in, const nlohmann::json& input_manifest,
                          uint64_t shards_taken) {
  rundir::ManifestInput entry;
  entry.dir = in;
  entry.shards_taken = shards_taken;
  for (const auto& [platform, j] : drivers_of(in))
    if (j.is_object()) entry.drivers[platform] = j.value("renderer", "") + " | " + j.value("version", "");
  if (input_manifest.is_object())
    for (const char* key : {"slice", "host", "invocations", "status", "started", "finished", "failures"})
      if (input_manifest.contains(key)) entry.provenance[key] = input_manifest[key];
  return entry;
}

// The manifest: every input's provenance, the failures they recorded, the merged shard count. It
// describes what DIR holds however it was assembled: what an earlier merge into DIR took (its
// inputs, shard times and failures) and what ran in DIR itself (a gather's `run`) stay.
rundir::RunManifest merged_manifest(const MergeOptions& options, const rundir::Experiment& exp,
                            const std::vector<rundir::Shard>& plan,
                            const std::map<std::string, uint64_t>& taken_from,
                            const std::map<std::string, std::string>& driver_file,
                            MergeResult* result) {
  const std::string& out = options.out_dir;
  const rundir::RunManifest before =
      rundir::read_manifest_file_or_empty(rundir::run_folder::manifest(out));
  std::vector<rundir::RunManifest> inputs;
  std::vector<nlohmann::json> input_json;
  for (const std::string& in : options.inputs) {
    input_json.push_back(rundir::read_manifest_json(rundir::run_folder::manifest(in)));
    inputs.push_back(rundir::read_manifest(input_json.back(), rundir::run_folder::manifest(in)));
  }
  rundir::RunManifest m;
  m.schema = "renderaudit-manifest";
  m.schema_version = rundir::kManifestSchemaVersion;
  m.invocations = before.invocations;
  m.tool = {{"name", "renderaudit"}, {"version", rundir::project_version()}, {"commit", rundir::project_commit()}};
  m.conformance_rules = common_conformance_rules(inputs, options);
  m.experiment = rundir::ManifestExperiment{exp.name, rundir::run_folder::experiment(out), exp.hash,
                                            exp.seed, exp.platforms};
  m.host = rundir::host_description();
  m.merged = rundir::utc_now_iso8601();
  m.inputs.emplace();
  for (const rundir::ManifestInput& entry : before.inputs.value_or(std::vector<rundir::ManifestInput>{}))
    if (std::find(options.inputs.begin(), options.inputs.end(), entry.dir) == options.inputs.end())
      m.inputs->push_back(entry);  // an earlier merge's input, not merged again now
  m.failures = before.failures_or_none();
  std::map<std::string, std::string> reasons;  // of failed primitives, by failure_key
  add_failure_reasons(before, &reasons);
  // each shard's worker time, from whichever input ran it (for cost models and simulations)
  m.shard_seconds = before.shard_seconds.value_or(std::map<std::string, double>{});
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const std::string& in = options.inputs[i];
    const auto taken = taken_from.find(in);
    m.inputs->push_back(input_entry(in, input_json[i], taken == taken_from.end() ? 0 : taken->second));
    for (const auto& [id, seconds] : inputs[i].shard_seconds.value_or(std::map<std::string, double>{}))
      m.shard_seconds->emplace(id, seconds);  // the first that ran it
    for (const rundir::ManifestShardNote& f : inputs[i].failures_or_none())
      if (std::none_of(m.failures->begin(), m.failures->end(), [&](const rundir::ManifestShardNote& g) {
            return g.shard == f.shard && g.reason == f.reason;
          }))
        m.failures->push_back(f);
    add_failure_reasons(inputs[i], &reasons);
  }
  m.drivers = nlohmann::json::object();
  for (const auto& [platform, path] : driver_file)
    m.drivers[platform] = util::read_json_or_null(rundir::run_folder::driver(out, platform));
  m.shards = rundir::ManifestShardCounts{result->shards_total, result->shards_present,
                                 result->shards_in_several_inputs};
  // the crash and timeout records DIR holds now, whichever merge or run put them there
  m.failed_primitives.emplace();
  for (const FailedPrimitive& f : failed_primitives_in_records(out, plan, reasons))
    m.failed_primitives->push_back({f.shard, f.index, metrics::status_name(f.status), f.reason});
  result->failed_primitives = m.failed_primitives->size();
  m.status = !result->missing.empty()       ? "failed"
             : !m.failed_primitives->empty() ? "complete-with-failed-primitives"
                                             : "complete";
  if (!result->missing.empty()) m.missing_shards = result->missing;
  return m;
}

}  // namespace

MergeResult merge_runs(const MergeOptions& options) {
  if (options.inputs.empty()) throw util::UserError("merge: name at least one run directory");
  const rundir::Experiment exp = common_experiment(options);
  const std::vector<rundir::Shard> plan = rundir::plan_shards(exp);
  require_one_driver_per_platform(options, plan);

  const std::unique_ptr<util::DirLock> lock = prepare_run_dir(exp, options.out_dir, "merge");
  MergeResult result;
  result.shards_total = plan.size();
  const std::map<std::string, uint64_t> taken_from = copy_shards(options, plan, &result);
  // the driver files: the first input's of each platform
  std::map<std::string, std::string> driver_file;
  for (auto it = options.inputs.rbegin(); it != options.inputs.rend(); ++it)
    for (const auto& [platform, j] : drivers_of(*it))
      driver_file[platform] = rundir::run_folder::driver(*it, platform);
  for (const auto& [platform, path] : driver_file)
    copy_atomically(path, rundir::run_folder::driver(options.out_dir, platform));

  rundir::write_manifest(rundir::run_folder::manifest(options.out_dir),
                         merged_manifest(options, exp, plan, taken_from, driver_file, &result));
  return result;
}

}  // namespace ra::runner
