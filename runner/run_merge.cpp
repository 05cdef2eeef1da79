// Gathering run directories of one experiment into one (see the header).
#include "runner/run_merge.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <nlohmann/json.hpp>

#include "metrics/conformance.h"
#include "runner/experiment.h"
#include "runner/manifest.h"
#include "runner/recorded_failures.h"
#include "runner/run_dir.h"
#include "runner/shard.h"
#include "runner/shard_file.h"
#include "util/atomic_file.h"
#include "util/errors.h"
#include "util/json_file.h"

namespace fs = std::filesystem;

namespace ra {
namespace {

// platform -> its driver file, from DIR/drivers/*.json
std::map<std::string, nlohmann::json> drivers_of(const std::string& dir) {
  std::map<std::string, nlohmann::json> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir + "/drivers", ec))
    if (e.path().extension() == ".json")
      out[e.path().stem().string()] = read_json_or_null(e.path().string());
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
  const std::string tmp = create_unique_temp(to);
  fs::copy_file(from, tmp, fs::copy_options::overwrite_existing, ec);
  if (ec) {
    fs::remove(tmp);
    throw std::runtime_error("cannot copy " + from + " to " + tmp + ": " + ec.message() +
                             free_space_note(to));
  }
  commit_file(tmp, to);
}

}  // namespace

MergeResult merge_runs(const MergeOptions& options) {
  if (options.inputs.empty()) throw UserError("merge: name at least one run directory");
  // The inputs: one experiment, one driver per platform.
  std::vector<Experiment> experiments;
  for (const std::string& in : options.inputs) {
    std::error_code ec;
    if (in == options.out_dir || fs::equivalent(in, options.out_dir, ec))
      throw UserError("merge: " + in + " is both an input and --out");
    if (!fs::exists(in + "/experiment.toml"))
      throw UserError("merge: " + in + ": not a run directory (no experiment.toml)");
    experiments.push_back(load_experiment(in + "/experiment.toml"));
    if (experiments.back().hash != experiments.front().hash) {
      throw UserError("merge: " + in + " holds experiment " + experiments.back().name + " (hash " +
                      experiments.back().hash + "), " + options.inputs.front() + " holds " +
                      experiments.front().name + " (hash " + experiments.front().hash +
                      "): only slices of one experiment can be merged");
    }
  }
  const Experiment& exp = experiments.front();
  // [run] shard_size is outside the hash but names the records files: slices cut with another
  // size hold none of this plan's shards.
  for (std::size_t i = 1; i < experiments.size(); ++i)
    if (experiments[i].shard_size != exp.shard_size)
      throw UserError("merge: " + options.inputs[i] + " was cut into shards of " +
                      std::to_string(experiments[i].shard_size) + " primitives ([run] shard_size), " +
                      options.inputs.front() + " into shards of " + std::to_string(exp.shard_size) +
                      ": their records files name other shards; run the slices with one "
                      "shard_size");
  // Every platform an input holds records of must say which driver drew them.
  const std::vector<Shard> plan = plan_shards(exp);
  if (!options.allow_driver_mismatch) {
    for (const std::string& in : options.inputs) {
      std::set<std::string> platforms;
      for (const Shard& s : plan)
        if (!platforms.count(s.platform) && fs::exists(s.records_path(in)))
          platforms.insert(s.platform);
      for (const std::string& platform : platforms)
        if (!fs::exists(in + "/drivers/" + platform + ".json"))
          throw UserError("merge: " + in + " holds records of " + platform + " but no drivers/" +
                          platform + ".json, so the driver that drew them cannot be compared "
                          "with the other inputs' (--allow-driver-mismatch merges it anyway)");
    }
  }
  std::map<std::string, std::pair<std::string, std::string>> driver_seen;  // platform -> text, dir
  for (const std::string& in : options.inputs) {
    for (const auto& [platform, j] : drivers_of(in)) {
      if (!j.is_object()) continue;
      const std::string text = j.value("renderer", "") + " | " + j.value("version", "");
      const auto [it, first] = driver_seen.try_emplace(platform, text, in);
      if (!first && it->second.first != text && !options.allow_driver_mismatch) {
        throw UserError("merge: platform " + platform + " drew with '" + text + "' in " + in +
                        " but with '" + it->second.first + "' in " + it->second.second +
                        " (--allow-driver-mismatch merges them anyway)");
      }
    }
  }

  const std::unique_ptr<DirLock> lock = prepare_run_dir(exp, options.out_dir, "merge");
  const std::string& out = options.out_dir;
  MergeResult result;
  result.shards_total = plan.size();
  nlohmann::json taken_from = nlohmann::json::object();  // input dir -> shards copied from it
  for (const Shard& s : plan) {
    const std::string target = s.records_path(out);
    if (fs::exists(target) && check_shard_file(target, s.size()).empty()) {
      ++result.shards_present;  // an earlier merge put it there
      continue;
    }
    int holders = 0;
    for (const std::string& in : options.inputs) {
      const std::string source = s.records_path(in);
      if (!fs::exists(source) || !check_shard_file(source, s.size()).empty()) continue;
      if (++holders == 1) {
        copy_atomically(source, out + "/records/" + fs::path(source).filename().string());
        ++result.shards_copied;
        ++result.shards_present;
        taken_from[in] = taken_from.value(in, 0) + 1;
      }
    }
    if (holders > 1) ++result.shards_in_several_inputs;
    if (holders == 0) result.missing.push_back(s.id());
  }
  // the driver files: the first input's of each platform
  std::map<std::string, std::string> driver_file;
  for (auto it = options.inputs.rbegin(); it != options.inputs.rend(); ++it)
    for (const auto& [platform, j] : drivers_of(*it))
      driver_file[platform] = *it + "/drivers/" + platform + ".json";
  for (const auto& [platform, path] : driver_file)
    copy_atomically(path, out + "/drivers/" + platform + ".json");

  // The manifest: every input's provenance, the failures they recorded, the merged shard count.
  // It describes what DIR holds however it was assembled: what an earlier merge into DIR took
  // (its inputs, shard times and failures) and what ran in DIR itself (a gather's `run`) stay.
  nlohmann::json m = document_header("manifest", kManifestSchemaVersion, false);
  nlohmann::json before = read_json_or_null(out + "/manifest.json");
  if (!before.is_object()) before = nlohmann::json::object();
  if (before.contains("invocations")) m["invocations"] = before["invocations"];
  m["tool"] = {
      {"name", "renderaudit"}, {"version", project_version()}, {"commit", project_commit()}};
  // One version of the conformance rules for every input's records.
  int rules = 0;
  std::string rules_from;
  for (const std::string& in : options.inputs) {
    const std::string path = in + "/manifest.json";
    const int r = conformance_rules_of(read_json_or_null(path), path);
    if (r == 0) continue;
    if (rules != 0 && r != rules)
      throw UserError(rules_from + " was judged by conformance rules " + std::to_string(rules) +
                      ", " + path + " by " + std::to_string(r) + ": their records cannot be merged");
    rules = r, rules_from = path;
  }
  m["conformance_rules"] = rules != 0 ? rules : kConformanceRulesVersion;
  m["experiment"] = {{"name", exp.name},
                     {"file", out + "/experiment.toml"},
                     {"hash", exp.hash},
                     {"seed", exp.seed},
                     {"platforms", exp.platforms}};
  m["host"] = host_description();
  m["merged"] = utc_now_iso8601();
  nlohmann::json slices = nlohmann::json::array();
  for (const auto& entry : before.value("inputs", nlohmann::json::array()))
    if (entry.is_object() && entry.contains("dir") &&
        std::find(options.inputs.begin(), options.inputs.end(), entry["dir"]) ==
            options.inputs.end())
      slices.push_back(entry);  // an earlier merge's input, not merged again now
  nlohmann::json failures = before.value("failures", nlohmann::json::array());
  if (!failures.is_array()) failures = nlohmann::json::array();
  std::map<std::string, std::string> reasons;  // of failed primitives, by failure_key
  add_failure_reasons(before.value("failed_primitives", nlohmann::json::array()), &reasons);
  // each shard's worker time, from whichever input ran it (for cost models and simulations)
  nlohmann::json shard_seconds = before.value("shard_seconds", nlohmann::json::object());
  if (!shard_seconds.is_object()) shard_seconds = nlohmann::json::object();
  for (const std::string& in : options.inputs) {
    const nlohmann::json im = read_json_or_null(in + "/manifest.json");
    nlohmann::json drivers = nlohmann::json::object();
    for (const auto& [platform, j] : drivers_of(in))
      if (j.is_object())
        drivers[platform] = j.value("renderer", "") + " | " + j.value("version", "");
    nlohmann::json entry = {
        {"dir", in}, {"shards_taken", taken_from.value(in, 0)}, {"drivers", drivers}};
    if (im.is_object()) {
      for (const char* key :
           {"slice", "host", "invocations", "status", "started", "finished", "failures"})
        if (im.contains(key)) entry[key] = im[key];
      const nlohmann::json seconds_of = im.value("shard_seconds", nlohmann::json::object());
      for (const auto& [id, seconds] : seconds_of.items())
        if (!shard_seconds.contains(id)) shard_seconds[id] = seconds;
      for (const auto& f : im.value("failures", nlohmann::json::array()))
        if (std::find(failures.begin(), failures.end(), f) == failures.end()) failures.push_back(f);
      add_failure_reasons(im.value("failed_primitives", nlohmann::json::array()), &reasons);
    }
    slices.push_back(entry);
  }
  m["inputs"] = slices;
  m["drivers"] = nlohmann::json::object();
  for (const auto& [platform, path] : driver_file)
    m["drivers"][platform] = read_json_or_null(out + "/drivers/" + platform + ".json");
  m["shards"] = {{"total", result.shards_total},
                 {"complete", result.shards_present},
                 {"in_several_inputs", result.shards_in_several_inputs}};
  m["failures"] = failures;
  // the crash and timeout records DIR holds now, whichever merge or run put them there
  nlohmann::json failed = nlohmann::json::array();
  for (const FailedPrimitive& f : failed_primitives_in_records(out, plan, reasons))
    failed.push_back({{"shard", f.shard}, {"index", f.index}, {"status", status_name(f.status)},
                      {"reason", f.reason}});
  result.failed_primitives = failed.size();
  m["failed_primitives"] = failed;
  m["shard_seconds"] = shard_seconds;
  m["status"] = !result.missing.empty() ? "failed"
                : !failed.empty()       ? "complete-with-failed-primitives"
                                        : "complete";
  if (!result.missing.empty()) m["missing_shards"] = result.missing;
  write_manifest(out + "/manifest.json", m);
  return result;
}

}  // namespace ra
