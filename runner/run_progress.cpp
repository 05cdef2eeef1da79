// DIR/progress.json (see the header).
#include "runner/run_progress.h"

#include "rundir/run_folder.h"
#include "util/atomic_file.h"
#include "util/json_file.h"

namespace ra::runner {

nlohmann::json seconds_or_null(double s) { return s >= 0 ? nlohmann::json(s) : nlohmann::json(); }

nlohmann::json to_json(const RunProgress& p) {
  return {{"host", p.host},
          {"pid", p.pid},
          {"updated", p.updated_utc},
          {"shards_to_run", p.shards_to_run},
          {"shards_finished", p.shards_finished},
          {"running", p.running},
          {"failed", p.failed},
          {"primitives_done", p.primitives_done},
          {"primitives_todo", p.primitives_todo},
          {"elapsed_s", p.elapsed_s},
          {"left_s", seconds_or_null(p.left_s)},
          {"finished", p.finished}};
}

RunProgress run_progress_from_json(const nlohmann::json& j) {
  RunProgress p;
  if (!j.is_object()) return p;
  p.host = j.value("host", "");
  p.pid = j.value("pid", 0L);
  p.updated_utc = j.value("updated", "");
  p.shards_to_run = j.value("shards_to_run", size_t{0});
  p.shards_finished = j.value("shards_finished", size_t{0});
  p.running = j.value("running", std::vector<std::string>{});
  p.failed = j.value("failed", std::vector<std::string>{});
  p.primitives_done = j.value("primitives_done", 0ULL);
  p.primitives_todo = j.value("primitives_todo", 0ULL);
  p.elapsed_s = j.value("elapsed_s", 0.0);
  p.left_s = j.contains("left_s") && j["left_s"].is_number() ? j["left_s"].get<double>() : -1.0;
  p.finished = j.value("finished", false);
  return p;
}

std::string progress_path(const std::string& run_dir) {
  return rundir::run_folder::progress(run_dir);
}

void write_run_progress(const std::string& run_dir, const RunProgress& p) {
  try {
    util::write_file_atomic(progress_path(run_dir), to_json(p).dump(1) + "\n");
  } catch (const std::exception&) {
  }
}

RunProgress read_run_progress(const std::string& run_dir) {
  try {
    const std::string path = progress_path(run_dir);
    return run_progress_from_json(util::parse_json_document(util::read_file(path), path));
  } catch (const std::exception&) {
    return {};
  }
}

}  // namespace ra::runner
