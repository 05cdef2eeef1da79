// STATE/watch.json read and written (watch_state.h).
#include "triage/watch_state.h"

#include <filesystem>
#include <nlohmann/json.hpp>

#include "util/atomic_file.h"
#include "util/errors.h"
#include "util/git_ref_check.h"
#include "util/json_file.h"

namespace fs = std::filesystem;

namespace ra::triage {

LastNight read_last(const std::string& path) {
  LastNight l;
  std::error_code ec;
  if (!fs::exists(path, ec)) return l;
  const std::string start_again =
      "; remove the file to start again from a new baseline (the history keeps every night)";
  nlohmann::json j;
  try {
    j = util::parse_json_document(util::read_file(path), path);
  } catch (const nlohmann::json::parse_error& e) {
    throw util::UserError("watch: " + path + ": not a whole JSON document (it breaks off or is " +
                          "garbled at byte " + std::to_string(e.byte) + "; a write cut short?)" +
                          start_again);
  } catch (const std::exception& e) {
    throw util::UserError("watch: " + path + ": cannot be read (" + e.what() + ")" + start_again);
  }
  if (!j.is_object())
    throw util::UserError("watch: " + path +
                          ": must be a JSON object (commit, build_dir, branch, source)" + start_again);
  const auto text = [&](const char* key, bool required) -> std::string {
    if (!j.contains(key)) {
      if (required)
        throw util::UserError("watch: " + path + ": " + key + ": missing" + start_again);
      return "";
    }
    if (!j[key].is_string())
      throw util::UserError("watch: " + path + ": " + key + ": must be a string" + start_again);
    return j[key].get<std::string>();
  };
  l.commit = text("commit", true);
  l.build_dir = text("build_dir", true);
  l.branch = text("branch", false);
  l.source = text("source", false);
  if (const std::string why = util::commit_hash_problem(l.commit); !why.empty())
    throw util::UserError("watch: " + path + ": commit: " + why + start_again);
  // "" is a tree that was detached on the night that wrote the file: no branch to return to.
  if (!l.branch.empty())
    if (const std::string why = util::branch_name_problem(l.branch); !why.empty())
      throw util::UserError("watch: " + path + ": branch: " + why + start_again);
  if (l.build_dir.empty() || l.build_dir[0] != '/')
    throw util::UserError("watch: " + path + ": build_dir: must be an absolute path" + start_again);
  return l;
}

void write_last(const std::string& path, const LastNight& last) {
  util::write_file_atomic(path, nlohmann::json{{"commit", last.commit},
                                               {"build_dir", last.build_dir},
                                               {"branch", last.branch},
                                               {"source", last.source}}
                                    .dump(2) +
                                    "\n");
}

}  // namespace ra::triage
