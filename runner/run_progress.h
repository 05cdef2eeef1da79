// DIR/progress.json: what a `run` at work is doing, rewritten atomically every few seconds and at
// its end, so that `renderaudit status` (another process, maybe on another machine of a shared
// file system) can say what is running and how long is left without touching the run.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace ra::runner {

struct RunProgress {
  std::string host;
  long pid = 0;
  std::string updated_utc;            // ISO 8601
  size_t shards_to_run = 0;           // by this invocation
  size_t shards_finished = 0;         // by this invocation
  std::vector<std::string> running;   // shard ids with a worker now
  std::vector<std::string> failed;    // shard ids whose worker failed (this invocation)
  unsigned long long primitives_done = 0, primitives_todo = 0;
  double elapsed_s = 0;
  double left_s = -1;                 // estimate from the rate so far; negative: not known yet
  bool finished = false;              // the invocation has ended (the manifest says how)
};

nlohmann::json to_json(const RunProgress& p);  // an unknown left_s is written as null
// Seconds as JSON: null when negative (the "not known" of left_s), else the number.
nlohmann::json seconds_or_null(double s);
RunProgress run_progress_from_json(const nlohmann::json& j);  // missing keys keep their defaults

std::string progress_path(const std::string& run_dir);  // DIR/progress.json

// Writes DIR/progress.json atomically; a failure (a full disk) is ignored: progress is a courtesy,
// the manifest and the shard files are what count.
void write_run_progress(const std::string& run_dir, const RunProgress& p);

// DIR/progress.json, or nullopt-like empty `host` when absent or unreadable.
RunProgress read_run_progress(const std::string& run_dir);

}  // namespace ra::runner
