#include "runner/manifest.h"

#include "util/atomic_file.h"
#include "util/errors.h"

#include <sys/utsname.h>
#include <unistd.h>

#include <fcntl.h>

#include <ctime>
#include <stdexcept>
#include <sys/stat.h>
#include <fstream>
#include <thread>

namespace ra {

std::string project_commit() { return RA_COMMIT; }
std::string project_version() { return "0.1.0"; }

nlohmann::json host_description() {
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  std::string cpu = "unknown";
  std::ifstream info("/proc/cpuinfo");
  for (std::string line; std::getline(info, line);) {
    if (line.rfind("model name", 0) == 0) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  }
  struct utsname u {};
  ::uname(&u);
  return {{"hostname", host},
          {"cpu", cpu},
          {"cores", std::thread::hardware_concurrency()},
          {"os", std::string(u.sysname) + " " + u.release + " " + u.machine}};
}

std::string utc_now_iso8601() {
  std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

nlohmann::json document_header(const std::string& name, int version, bool provenance) {
  nlohmann::json j = {{"schema", "renderaudit-" + name}, {"schema_version", version}};
  if (provenance) {
    j["tool"] = {{"name", "renderaudit"}, {"version", project_version()}, {"commit", project_commit()}};
    j["host"] = host_description();
    j["created_utc"] = utc_now_iso8601();
  }
  return j;
}

namespace {

[[noreturn]] void bad_field(const std::string& path, const std::string& key,
                            const std::string& rule, const nlohmann::json& found) {
  std::string text = found.dump();
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  throw UserError(path + ": '" + key + "' must be " + rule + " (found " + text + ")");
}

std::string text_field(const nlohmann::json& object, const std::string& path,
                       const std::string& key, const std::string& shown_key) {
  if (!object.contains(key)) return "";
  if (!object[key].is_string()) bad_field(path, shown_key, "a string", object[key]);
  return object[key].get<std::string>();
}

// An integer in [low, high] at `key` of `object`.
int int_field(const nlohmann::json& object, const std::string& path, const std::string& key,
              const std::string& shown_key, int64_t low, int64_t high) {
  const std::string rule =
      "an integer from " + std::to_string(low) + " to " + std::to_string(high);
  if (!object.contains(key) || !object[key].is_number_integer())
    bad_field(path, shown_key, rule, object.value(key, nlohmann::json()));
  const int64_t v = object[key].get<int64_t>();
  if (v < low || v > high) bad_field(path, shown_key, rule, object[key]);
  return int(v);
}

}  // namespace

ManifestFields read_manifest_fields(const nlohmann::json& m, const std::string& path) {
  ManifestFields f;
  if (m.is_null()) return f;
  if (!m.is_object()) bad_field(path, "(the document)", "a JSON object", m);
  f.status = text_field(m, path, "status", "status");
  if (m.contains("experiment")) {
    if (!m["experiment"].is_object()) bad_field(path, "experiment", "an object", m["experiment"]);
    f.experiment_name = text_field(m["experiment"], path, "name", "experiment.name");
  }
  if (m.contains("platforms_run")) {
    const auto& p = m["platforms_run"];
    if (!p.is_array()) bad_field(path, "platforms_run", "an array of platform names", p);
    for (const auto& name : p) {
      if (!name.is_string()) bad_field(path, "platforms_run", "an array of platform names", p);
      f.platforms_run.push_back(name.get<std::string>());
    }
    f.has_platforms_run = true;
  }
  if (m.contains("slice")) {
    const auto& sl = m["slice"];
    if (!sl.is_object()) bad_field(path, "slice", "an object {index, count}", sl);
    f.slice_count = int_field(sl, path, "count", "slice.count", 1, 100000);
    f.slice_index = int_field(sl, path, "index", "slice.index", 1, f.slice_count);
    f.has_slice = true;
  }
  if (m.contains("failures")) {
    const auto& failures = m["failures"];
    if (!failures.is_array()) bad_field(path, "failures", "an array", failures);
    for (const auto& e : failures) {
      if (!e.is_object()) bad_field(path, "failures[]", "an object {shard, reason}", e);
      f.failed_shards.push_back(text_field(e, path, "shard", "failures[].shard"));
    }
  }
  return f;
}

namespace {

// Overwrites `path` from offset 0 with `text` padded with spaces to the file's current size (JSON
// allows trailing white space): no block is allocated, so it works on a full disk.
bool overwrite_in_place(const std::string& path, std::string text) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) return false;
  struct stat st {};
  bool ok = ::fstat(fd, &st) == 0 && text.size() <= size_t(st.st_size);
  if (ok) {
    text.append(size_t(st.st_size) - text.size(), ' ');
    ok = ::pwrite(fd, text.data(), text.size(), 0) == ssize_t(text.size()) && ::fsync(fd) == 0;
  }
  ::close(fd);
  return ok;
}

}  // namespace

void write_manifest(const std::string& path, const nlohmann::json& manifest) {
  try {
    write_file_atomic(path, manifest.dump(2) + "\n");
    return;
  } catch (const std::runtime_error& e) {
    const std::string reason = std::string("cannot write the manifest: ") + e.what();
    // Shortest first that still says what the run was: drop the bulky parts, then everything.
    nlohmann::json failed = manifest;
    for (const char* bulky : {"invocations", "drivers", "failed_primitives", "failures", "host"})
      failed.erase(bulky);
    failed["status"] = "failed";
    failed["reason"] = reason;
    bool saved = overwrite_in_place(path, failed.dump() + "\n");
    if (!saved) {  // the essentials, with as much of the reason as the file has room for
      struct stat st {};
      const size_t room = ::stat(path.c_str(), &st) == 0 ? size_t(st.st_size) : 0;
      nlohmann::json minimal = {{"schema_version", kManifestSchemaVersion}, {"status", "failed"}};
      minimal["experiment"] = manifest.value("experiment", nlohmann::json::object()).value("name", "");
      const size_t overhead = minimal.dump().size() + std::string(",\"reason\":\"\"\n").size();
      if (room > overhead) {
        minimal["reason"] = reason.substr(0, room - overhead);
        while (minimal.dump().size() + 1 > room && !minimal["reason"].get<std::string>().empty())
          minimal["reason"] = minimal["reason"].get<std::string>().substr(
              0, minimal["reason"].get<std::string>().size() - 1);  // escapes took room
      }
      saved = overwrite_in_place(path, minimal.dump() + "\n");
    }
    throw std::runtime_error(reason + (saved ? "; " + path + " now says \"failed\""
                                             : "; " + path + " could not be updated either"));
  }
}

}  // namespace ra

namespace ra {

int conformance_rules_of(const nlohmann::json& manifest, const std::string& path) {
  if (!manifest.is_object()) return 0;
  if (!manifest.contains("conformance_rules")) return manifest.contains("invocations") ? 1 : 0;
  const nlohmann::json& v = manifest["conformance_rules"];
  if (!v.is_number_integer() || v.get<int64_t>() < 1 || v.get<int64_t>() > 1000)
    throw UserError(path + ": \"conformance_rules\" must be a positive integer, not " + v.dump());
  return v.get<int>();
}

}  // namespace ra
