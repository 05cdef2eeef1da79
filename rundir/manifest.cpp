#include "rundir/manifest.h"

#include "util/atomic_file.h"
#include "util/errors.h"
#include "util/json_file.h"

#include <sys/utsname.h>
#include <unistd.h>

#include <fcntl.h>

#include <algorithm>
#include <ctime>
#include <filesystem>
#include <stdexcept>
#include <sys/stat.h>
#include <fstream>
#include <thread>

namespace ra::rundir {

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

bool has_document_header(const nlohmann::json& doc, const std::string& name, int version) {
  if (!doc.is_object()) return false;
  const auto schema = doc.find("schema");
  const auto schema_version = doc.find("schema_version");
  return schema != doc.end() && schema->is_string() &&
         schema->get<std::string>() == "renderaudit-" + name && schema_version != doc.end() &&
         schema_version->is_number_integer() && schema_version->get<int64_t>() == version;
}

void require_document_header(const nlohmann::json& doc, const std::string& name, int version,
                             const std::string& path, const std::string& remedy) {
  if (has_document_header(doc, name, version)) return;
  throw util::UserError(path + ": expected schema renderaudit-" + name + " version " +
                        std::to_string(version) + (remedy.empty() ? "" : " (" + remedy + ")"));
}

namespace {

using json = nlohmann::json;

[[noreturn]] void bad_field(const std::string& path, const std::string& key,
                            const std::string& rule, const json& found) {
  std::string text = found.dump();
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  throw util::UserError(path + ": '" + key + "' must be " + rule + " (found " + text + ")");
}

// Reads the fields of one JSON object of a manifest, each named in errors by its path from the
// document's root ("slice.count", "failures[].shard").
class FieldReader {
 public:
  FieldReader(const json& object, const std::string& path, std::string prefix, const char* rule)
      : o_(object), path_(path), prefix_(std::move(prefix)) {
    if (!o_.is_object()) bad_field(path_, prefix_.empty() ? "(the document)" : shown(""), rule, o_);
  }
  bool has(const char* key) const { return o_.contains(key); }
  const json& at(const char* key) const { return o_[key]; }
  std::string shown(const std::string& key) const {
    if (prefix_.empty()) return key;
    return key.empty() ? prefix_ : prefix_ + "." + key;
  }
  [[noreturn]] void bad(const char* key, const std::string& rule) const {
    bad_field(path_, shown(key), rule, o_.value(key, json()));
  }

  std::string text(const char* key) const {  // "" when absent
    if (!has(key)) return "";
    if (!at(key).is_string()) bad(key, "a string");
    return at(key).get<std::string>();
  }
  std::string required_text(const char* key) const {
    if (!has(key)) bad(key, "a string");
    return text(key);
  }
  uint64_t count(const char* key) const {
    // a parsed 7 is unsigned, a 7 set in C++ from an int is signed
    const bool ok = has(key) && (at(key).is_number_unsigned() ||
                                 (at(key).is_number_integer() && at(key).get<int64_t>() >= 0));
    if (!ok) bad(key, "an integer from 0");
    return at(key).get<uint64_t>();
  }
  std::optional<uint64_t> optional_count(const char* key) const {
    if (!has(key)) return std::nullopt;
    return count(key);
  }
  int64_t integer(const char* key, int64_t low, int64_t high) const {
    const std::string rule = "an integer from " + std::to_string(low) + " to " + std::to_string(high);
    if (!has(key) || !at(key).is_number_integer()) bad(key, rule);
    const int64_t v = at(key).get<int64_t>();
    if (v < low || v > high) bad(key, rule);
    return v;
  }
  std::optional<double> seconds(const char* key) const {
    if (!has(key)) return std::nullopt;
    if (!at(key).is_number()) bad(key, "a number of seconds");
    return at(key).get<double>();
  }
  std::vector<std::string> texts(const char* key, const char* rule) const {
    if (!at(key).is_array()) bad(key, rule);
    std::vector<std::string> out;
    for (const json& e : at(key)) {
      if (!e.is_string()) bad(key, rule);
      out.push_back(e.get<std::string>());
    }
    return out;
  }
  // Each element of the array at `key` through `read(element, reader)`.
  template <typename T, typename Read>
  std::vector<T> list(const char* key, const char* element_rule, Read read) const {
    if (!at(key).is_array()) bad(key, "an array");
    std::vector<T> out;
    for (const json& e : at(key))
      out.push_back(read(FieldReader(e, path_, shown(key) + "[]", element_rule)));
    return out;
  }

 private:
  const json& o_;
  const std::string& path_;
  std::string prefix_;
};

ManifestShardNote read_note(const FieldReader& f) {
  return {f.required_text("shard"), f.text("reason")};
}

ManifestInvocation read_invocation(const FieldReader& f) {
  ManifestInvocation i;
  i.started = f.text("started");
  i.jobs = f.count("jobs");
  i.shards_to_run = f.count("shards_to_run");
  i.elapsed_s = f.seconds("elapsed_s");
  i.shard_order = f.text("shard_order");
  i.worker_busy_s = f.seconds("worker_busy_s");
  i.worker_processes = f.optional_count("worker_processes");
  i.workers = f.text("workers");
  i.idle_core_s = f.seconds("idle_core_s");
  return i;
}

ManifestInput read_input(const FieldReader& f, const json& entry) {
  ManifestInput in;
  in.dir = f.required_text("dir");
  in.shards_taken = f.count("shards_taken");
  if (f.has("drivers")) {
    if (!f.at("drivers").is_object()) f.bad("drivers", "an object of platform -> driver text");
    for (const auto& [platform, text] : f.at("drivers").items()) {
      if (!text.is_string()) f.bad("drivers", "an object of platform -> driver text");
      in.drivers[platform] = text.get<std::string>();
    }
  }
  for (const auto& [key, value] : entry.items())
    if (key != "dir" && key != "shards_taken" && key != "drivers") in.provenance[key] = value;
  return in;
}

// The keys read_manifest knows; the others are kept in `unknown`.
const char* const kKnownKeys[] = {
    "schema", "schema_version", "status", "reason", "conformance_rules", "experiment", "tool",
    "host", "platforms_run", "slice", "invocations", "started", "finished", "merged", "drivers",
    "shard_seconds", "shards", "failures", "damaged_shards_redone", "failed_primitives",
    "wrong_renderer", "missing_shards", "inputs"};

void read_experiment(const json& m, const std::string& path, RunManifest* out) {
  if (!m.contains("experiment")) return;
  ManifestExperiment e;
  if (m["experiment"].is_string()) {  // the shortest manifest a full disk leaves: its name only
    e.name = m["experiment"].get<std::string>();
    out->experiment = e;
    return;
  }
  const FieldReader f(m["experiment"], path, "experiment", "an object");
  e.name = f.text("name");
  e.file = f.text("file");
  e.hash = f.text("hash");
  e.seed = f.optional_count("seed");
  if (f.has("platforms")) e.platforms = f.texts("platforms", "an array of platform names");
  out->experiment = e;
}

void read_run_fields(const FieldReader& f, const std::string& path, RunManifest* m) {
  if (f.has("platforms_run"))
    m->platforms_run = f.texts("platforms_run", "an array of platform names");
  if (f.has("slice")) {
    const FieldReader sl(f.at("slice"), path, "slice", "an object {index, count}");
    ManifestSlice slice;
    slice.count = int(sl.integer("count", 1, 100000));
    slice.index = int(sl.integer("index", 1, slice.count));
    slice.shards = sl.optional_count("shards");
    m->slice = slice;
  }
  if (f.has("invocations"))
    m->invocations = f.list<ManifestInvocation>("invocations", "an object", read_invocation);
  if (f.has("shard_seconds")) {
    const FieldReader s(f.at("shard_seconds"), path, "shard_seconds", "an object");
    std::map<std::string, double> seconds;
    for (const auto& [id, v] : f.at("shard_seconds").items()) {
      if (!v.is_number()) bad_field(path, "shard_seconds." + id, "a number of seconds", v);
      seconds[id] = v.get<double>();
    }
    m->shard_seconds = seconds;
  }
  if (f.has("shards")) {
    const FieldReader s(f.at("shards"), path, "shards", "an object {total, complete}");
    m->shards = ManifestShardCounts{s.count("total"), s.count("complete"),
                                    s.optional_count("in_several_inputs")};
  }
}

void read_failure_fields(const FieldReader& f, RunManifest* m) {
  const char* note_rule = "an object {shard, reason}";
  if (f.has("failures"))
    m->failures = f.list<ManifestShardNote>("failures", note_rule, read_note);
  if (f.has("damaged_shards_redone"))
    m->damaged_shards_redone = f.list<ManifestShardNote>("damaged_shards_redone", note_rule, read_note);
  if (f.has("failed_primitives"))
    m->failed_primitives = f.list<ManifestFailedPrimitive>(
        "failed_primitives", "an object {shard, index, status, reason}", [](const FieldReader& p) {
          return ManifestFailedPrimitive{p.required_text("shard"), p.count("index"),
                                         p.text("status"), p.text("reason")};
        });
  if (f.has("missing_shards"))
    m->missing_shards = f.texts("missing_shards", "an array of shard ids");
}

void put_text(json& j, const char* key, const std::string& v) {
  if (!v.empty()) j[key] = v;
}

json note_json(const std::vector<ManifestShardNote>& notes) {
  json out = json::array();
  for (const ManifestShardNote& n : notes) out.push_back({{"shard", n.shard}, {"reason", n.reason}});
  return out;
}

json invocation_json(const ManifestInvocation& i) {
  json j = {{"jobs", i.jobs}, {"shards_to_run", i.shards_to_run}};
  put_text(j, "started", i.started);
  if (i.elapsed_s) j["elapsed_s"] = *i.elapsed_s;
  put_text(j, "shard_order", i.shard_order);
  if (i.worker_busy_s) j["worker_busy_s"] = *i.worker_busy_s;
  if (i.worker_processes) j["worker_processes"] = *i.worker_processes;
  put_text(j, "workers", i.workers);
  if (i.idle_core_s) j["idle_core_s"] = *i.idle_core_s;
  return j;
}

}  // namespace

RunManifest read_manifest(const json& m, const std::string& path) {
  RunManifest out;
  if (m.is_null()) return out;
  const FieldReader f(m, path, "", "a JSON object");
  out.schema = f.text("schema");
  if (f.has("schema_version")) out.schema_version = f.integer("schema_version", 1, 1000);
  out.status = f.text("status");
  out.reason = f.text("reason");
  if (f.has("conformance_rules"))
    out.conformance_rules = int(f.integer("conformance_rules", 1, 1000));
  read_experiment(m, path, &out);
  if (f.has("tool")) out.tool = m["tool"];
  if (f.has("host")) out.host = m["host"];
  out.started = f.text("started");
  out.finished = f.text("finished");
  out.merged = f.text("merged");
  if (f.has("drivers")) {
    FieldReader(m["drivers"], path, "drivers", "an object of platform -> driver");
    out.drivers = m["drivers"];
  }
  read_run_fields(f, path, &out);
  read_failure_fields(f, &out);
  out.wrong_renderer = f.text("wrong_renderer");
  if (f.has("inputs")) {
    const json& inputs = m["inputs"];
    if (!inputs.is_array()) bad_field(path, "inputs", "an array", inputs);
    out.inputs.emplace();
    for (const json& e : inputs)
      out.inputs->push_back(read_input(FieldReader(e, path, "inputs[]", "an object {dir, ...}"), e));
  }
  for (const auto& [key, value] : m.items())
    if (std::find(std::begin(kKnownKeys), std::end(kKnownKeys), key) == std::end(kKnownKeys))
      out.unknown[key] = value;
  return out;
}

RunManifest read_manifest_file(const std::string& path) {
  const json m = read_manifest_json(path);
  if (m.is_null()) throw util::UserError(path + ": missing (not a run directory?)");
  return read_manifest(m, path);
}

nlohmann::json read_manifest_json(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return nullptr;
  std::string text;
  try {
    text = util::read_file(path);
  } catch (const std::exception& e) {
    throw util::UserError(e.what());
  }
  try {
    return util::parse_json_document(text, path);
  } catch (const json::exception& e) {
    throw util::UserError(path + ": not a JSON document (" + e.what() +
                          "); `run` of the same experiment into this folder keeps it as "
                          "manifest.json.damaged (or .damaged.2, ... beside copies kept earlier) "
                          "and starts a new manifest");
  }
}

RunManifest read_manifest_file_or_empty(const std::string& path) {
  return read_manifest(read_manifest_json(path), path);
}

json manifest_json(const RunManifest& m) {
  json j = m.unknown.is_object() ? m.unknown : json::object();
  put_text(j, "schema", m.schema);
  if (m.schema_version) j["schema_version"] = *m.schema_version;
  put_text(j, "status", m.status);
  put_text(j, "reason", m.reason);
  if (m.conformance_rules) j["conformance_rules"] = *m.conformance_rules;
  if (m.experiment) {
    const ManifestExperiment& e = *m.experiment;
    j["experiment"] = {{"name", e.name}, {"file", e.file}, {"hash", e.hash},
                       {"platforms", e.platforms}};
    if (e.seed) j["experiment"]["seed"] = *e.seed;
  }
  if (!m.tool.is_null()) j["tool"] = m.tool;
  if (!m.host.is_null()) j["host"] = m.host;
  if (m.platforms_run) j["platforms_run"] = *m.platforms_run;
  if (m.slice) {
    j["slice"] = {{"index", m.slice->index}, {"count", m.slice->count}};
    if (m.slice->shards) j["slice"]["shards"] = *m.slice->shards;
  }
  if (m.invocations) {
    j["invocations"] = json::array();
    for (const ManifestInvocation& i : *m.invocations) j["invocations"].push_back(invocation_json(i));
  }
  put_text(j, "started", m.started);
  put_text(j, "finished", m.finished);
  put_text(j, "merged", m.merged);
  if (!m.drivers.is_null()) j["drivers"] = m.drivers;
  if (m.shard_seconds) j["shard_seconds"] = json(*m.shard_seconds);
  if (m.shards) {
    j["shards"] = {{"total", m.shards->total}, {"complete", m.shards->complete}};
    if (m.shards->in_several_inputs) j["shards"]["in_several_inputs"] = *m.shards->in_several_inputs;
  }
  if (m.failures) j["failures"] = note_json(*m.failures);
  if (m.damaged_shards_redone) j["damaged_shards_redone"] = note_json(*m.damaged_shards_redone);
  if (m.failed_primitives) {
    j["failed_primitives"] = json::array();
    for (const ManifestFailedPrimitive& f : *m.failed_primitives)
      j["failed_primitives"].push_back(
          {{"shard", f.shard}, {"index", f.index}, {"status", f.status}, {"reason", f.reason}});
  }
  put_text(j, "wrong_renderer", m.wrong_renderer);
  if (m.missing_shards) j["missing_shards"] = *m.missing_shards;
  if (m.inputs) {
    j["inputs"] = json::array();
    for (const ManifestInput& in : *m.inputs) {
      json e = in.provenance.is_object() ? in.provenance : json::object();
      e["dir"] = in.dir;
      e["shards_taken"] = in.shards_taken;
      e["drivers"] = json(in.drivers);
      j["inputs"].push_back(e);
    }
  }
  return j;
}

int RunManifest::rules_judged_by() const {
  if (conformance_rules) return *conformance_rules;
  return invocations ? 1 : 0;
}

const std::vector<ManifestShardNote>& RunManifest::failures_or_none() const {
  static const std::vector<ManifestShardNote> none;
  return failures ? *failures : none;
}

const ManifestInvocation* RunManifest::last_invocation() const {
  return invocations && !invocations->empty() ? &invocations->back() : nullptr;
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

void write_manifest_json(const std::string& path, const nlohmann::json& manifest) {
  try {
    util::write_file_atomic(path, manifest.dump(2) + "\n");
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

}  // namespace

void write_manifest(const std::string& path, const RunManifest& manifest) {
  write_manifest_json(path, manifest_json(manifest));
}

}  // namespace ra::rundir
