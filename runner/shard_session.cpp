#include "runner/shard_session.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "rundir/run_folder.h"
#include "util/atomic_file.h"
#include "rundir/shard_file.h"
#include "runner/case_measurement.h"
#include "runner/effective_subpixel.h"
#include "rundir/experiment.h"
#include "rundir/manifest.h"
#include "platforms/driver_loading.h"
#include "platforms/platform.h"
#include "platforms/renderer_check.h"

namespace ra::runner {

// The run's driver file, written by the first worker of each platform: only that worker pays
// for measuring the timer (hundreds of milliseconds on softpipe: it was a third of a softpipe
// point shard's time when every worker measured it).
static void write_driver_info(const std::string& run_dir, const rundir::PlatformSpec& spec,
                              platforms::Platform& platform,
                              const runner::EffectiveSubpixel& effective) {
  const std::string path = rundir::run_folder::driver(run_dir, spec.name);
  struct stat st;
  if (::stat(path.c_str(), &st) == 0) return;
  platform.measure_timer_over_cpu();
  const platforms::DriverInfo info = platform.driver_info();
  nlohmann::json j = {{"renderer", info.renderer},           {"version", info.version},
                      {"vendor", info.vendor},               {"subpixel_bits", info.subpixel_bits},
                      {"timer_query", info.timer_query},     {"max_samples", info.max_samples},
                      {"backend", info.backend},             {"clock", info.clock},
                      {"layered", info.layered},
                      {"timer_over_cpu", std::isnan(info.timer_over_cpu)
                                             ? nlohmann::json()
                                             : nlohmann::json(info.timer_over_cpu)}};
  j["effective_subpixel"] = runner::effective_subpixel_json(effective);
  if (spec.draws_with_vulkan()) {  // the Vulkan rules depend on these (metrics/conformance.h)
    j["line_subpixel_bits"] = info.line_subpixel_bits;
    j["strict_lines"] = info.strict_lines;
    j["line_modes"] = info.line_modes;
    j["line_mode"] = info.line_mode;
  }
  // The build that drew (none: the installed driver) and every driver library this process
  // loaded, by path and content fingerprint: what a re-render must load to draw the same.
  if (spec.draws_with_driver()) {
    nlohmann::json libs = nlohmann::json::array();
    for (const platforms::LoadedLibrary& l : platforms::loaded_driver_libraries())
      libs.push_back({{"path", l.path}, {"fnv1a64", l.fnv1a64}});
    j["build"] = {{"name", spec.build.empty() ? nlohmann::json() : nlohmann::json(spec.build)},
                  {"folder", spec.build.empty() ? nlohmann::json() : nlohmann::json(spec.build_dir)},
                  {"libraries", libs}};
  }
  j.update(rundir::document_header("driver", 1, false));
  // Several shards may race here; each writes a complete file under its own temporary name.
  util::write_file_atomic(path, j.dump(2) + "\n");
}

ShardSession::ShardSession(std::string run_dir, const rundir::Experiment& exp, std::string platform)
    : run_dir_(std::move(run_dir)), exp_(exp), platform_name_(std::move(platform)) {}

ShardSession::~ShardSession() = default;

void ShardSession::run(const rundir::Shard& shard, const std::string& records_dir) {
  if (shard.platform != platform_name_)
    throw std::logic_error("shard " + shard.id() + " sent to a session of " + platform_name_);
  const geometry::View* view = nullptr;
  for (const geometry::View& v : exp_.views)
    if (v.id == shard.view) view = &v;
  if (!view) throw std::runtime_error("shard " + shard.id() + ": no such view");

  const bool exact = shard.platform == "reference";
  if (!platform_) {
    const rundir::PlatformSpec spec = rundir::experiment_platform(exp_, shard.platform);
    platform_ = platforms::create_platform(spec, rundir::fault_plan_for(exp_, spec));
    // One driver per record: a process that loaded another driver than the one that made the
    // run's records stops here, before drawing anything (exit status 2).
    platforms::require_run_driver(run_dir_, shard.platform, platform_->driver_info());
    // Every process measures the grid itself (about 96 small triangles: tens of milliseconds),
    // so that its verdicts never depend on which process wrote the driver file first.
    effective_ =
        exact ? runner::EffectiveSubpixel{} : runner::measure_effective_subpixel(*platform_);
    write_driver_info(run_dir_, spec, *platform_, effective_);
  }
  platform_->set_view(*view);
  runner::CaseComparison comparison(!exact, effective_.grid);
  comparison.line_rule =
      runner::line_rule_for(rundir::experiment_platform(exp_, shard.platform), platform_->driver_info());

  const std::string path =
      records_dir.empty()
          ? shard.records_path(run_dir_, exp_.records_format)
          : records_dir + "/" + shard.id() + rundir::records_extension(exp_.records_format);
  // A temporary of this writer alone: a second writer (a run that ignored the lock) cannot
  // interleave its rows with ours, and a killed one leaves only its own temporary behind.
  const std::string tmp = util::create_unique_temp(path);
  try {
    rundir::RecordsFileWriter out(tmp, exp_.records_format);
    constexpr uint64_t kChunk = 1024;  // primitives measured together (and batched inside)
    std::vector<geometry::Primitive> prims;
    for (uint64_t first = shard.begin; first < shard.end; first += kChunk) {
      prims.clear();
      for (uint64_t i = first; i < std::min(shard.end, first + kChunk); ++i)
        prims.push_back(geometry::make_primitive(exp_.seed, shard.kind, i));
      for (const metrics::Record& r :
           runner::measure_cases(shard.platform, *platform_, *view, prims, comparison, nullptr,
                                 max_batch_ ? max_batch_ : runner::kMaxBatch))
        out.write(r);
    }
    out.finish();
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
  util::commit_file(tmp, path);
}

void run_shard(const std::string& run_dir, const rundir::Experiment& exp, const rundir::Shard& shard,
               const std::string& records_dir) {
  ShardSession(run_dir, exp, shard.platform).run(shard, records_dir);
}

}  // namespace ra::runner
