// Test support for the audit tests (audit/*_test.cpp only): hand-written run directories, so the
// comparison, the verdict and the writers can be tested on exactly the records a case needs.
#pragma once

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rundir/experiment.h"
#include "metrics/records.h"
#include "rundir/run_folder.h"
#include "rundir/shard.h"
#include "rundir/shard_file.h"

namespace ra::audit::testing {

// A fresh directory under the system temp dir (removed first).
inline std::string fresh_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("renderaudit_audit_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(rundir::run_folder::records(dir.string()));
  return dir.string();
}

// An experiment of `points` points on `platforms` (TOML list body, e.g. "\"reference\"") in one
// 32 x 32 view (two with `orientations` = 2), cut into shards of `shard_size`.
inline std::string experiment_text(const std::string& platforms, int points, int shard_size,
                                   uint64_t seed = 5, int orientations = 1) {
  return "seed = " + std::to_string(seed) + "\nplatforms = [" + platforms +
         "]\n[views]\norientations = " + std::to_string(orientations) +
         "\nfov_deg = [60]\nwindows = [32]\nnear = 0.01\nfar = 10.0\n[primitives]\npoints = " +
         std::to_string(points) + "\n[run]\nshard_size = " + std::to_string(shard_size) + "\n";
}

// Writes DIR/experiment.toml and DIR/manifest.json (hash and seed as `run` writes them, drivers
// named "<platform> renderer" / "<platform> 1.0", the given shard failures); returns the
// experiment.
inline rundir::Experiment write_run(const std::string& dir, const std::string& text,
                                    const nlohmann::json& failures = nlohmann::json::array()) {
  std::ofstream(rundir::run_folder::experiment(dir)) << text;
  const rundir::Experiment exp =
      rundir::parse_experiment(text, rundir::run_folder::experiment(dir));
  nlohmann::json drivers = nlohmann::json::object();
  for (const auto& p : exp.platforms)
    drivers[p] = {{"renderer", p + " renderer"}, {"version", p + " 1.0"}};
  const nlohmann::json manifest = {
      {"schema_version", 1},
      {"experiment",
       {{"name", exp.name}, {"hash", exp.hash}, {"seed", exp.seed}, {"platforms", exp.platforms}}},
      {"drivers", drivers},
      {"failures", failures},
      {"status", failures.empty() ? "complete" : "failed"}};
  std::ofstream(rundir::run_folder::manifest(dir)) << manifest.dump(2);
  return exp;
}

// A true-visible point record of view `view` of `exp` with lit-pixel hash `hash` and PE `pe`.
inline metrics::Record point_record(const rundir::Experiment& exp, const std::string& platform,
                                    int view, uint64_t index, uint64_t hash, double pe) {
  const geometry::View& v = exp.views.at(std::size_t(view - 1));
  metrics::Record r;
  r.platform = platform;
  r.view = v.id, r.view_group = v.group, r.orientation = v.orientation;
  r.fov_deg = v.fov_deg, r.width = v.width, r.height = v.height, r.near = v.near, r.far = v.far;
  r.kind = "point";
  r.index = index;
  r.visibility = metrics::Visibility::kTrueVisible;
  r.pixels = 1;
  r.pe = pe;
  r.pe_norm = pe / 32;
  r.ref_diff = 0;
  r.pixel_hash = hash;
  r.render_us = 1;
  return r;
}

// Writes every planned point shard of `platform` in DIR, one record per index made by `make`
// (index -> record), sealed as `run` writes them; shards listed in `skip` (by id) are left out.
inline void write_points(const std::string& dir, const rundir::Experiment& exp,
                         const std::string& platform,
                         const std::function<metrics::Record(int view, uint64_t index)>& make,
                         const std::vector<std::string>& skip = {}) {
  for (const rundir::Shard& s : rundir::plan_shards(exp)) {
    if (s.platform != platform || s.kind != geometry::Kind::kPoint) continue;
    bool skipped = false;
    for (const auto& id : skip) skipped = skipped || id == s.id();
    if (skipped) continue;
    rundir::RecordsFileWriter out(s.records_path(dir, rundir::RecordsFormat::kCsv),
                                  rundir::RecordsFormat::kCsv);
    for (uint64_t i = s.begin; i < s.end; ++i) out.write(make(s.view, i));
    out.finish();
  }
}

}  // namespace ra::audit::testing
