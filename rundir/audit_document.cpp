// audit.json read back (see the header).
#include "rundir/audit_document.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "rundir/manifest.h"
#include "rundir/run_folder.h"
#include "util/atomic_file.h"
#include "util/errors.h"
#include "util/json_file.h"

namespace ra::rundir {
namespace {

using nlohmann::json;

// Field readers naming the file and the key of what is wrong.
struct Reader {
  std::string path;
  static std::string name_of(const std::string& where, const std::string& key) {
    return where.empty() ? key : where + "." + key;
  }
  [[noreturn]] void bad(const std::string& key, const std::string& what) const {
    throw util::UserError(path + ": '" + key + "' " + what +
                          "; run the audit again (renderaudit audit) to write it whole");
  }
  const json& at(const json& j, const std::string& key, const std::string& where) const {
    const std::string name = name_of(where, key);
    if (!j.is_object() || !j.contains(key)) bad(name, "is missing");
    return j.at(key);
  }
  std::string text(const json& j, const std::string& key, const std::string& where) const {
    const json& v = at(j, key, where);
    if (!v.is_string()) bad(name_of(where, key), "must be a string");
    return v.get<std::string>();
  }
  uint64_t count(const json& j, const std::string& key, const std::string& where) const {
    const json& v = at(j, key, where);
    if (!v.is_number_unsigned()) bad(name_of(where, key), "must be a whole number of 0 or more");
    return v.get<uint64_t>();
  }
  // a time ratio: a number, or null where none was formed
  double ratio(const json& j, const std::string& key, const std::string& where) const {
    const json& v = at(j, key, where);
    if (v.is_null()) return NAN;
    if (!v.is_number()) bad(name_of(where, key), "must be a number or null");
    return v.get<double>();
  }
  const json& list(const json& j, const std::string& key, const std::string& where) const {
    const json& v = at(j, key, where);
    if (!v.is_array()) bad(name_of(where, key), "must be a list");
    return v;
  }
};

// The verdict and what it rests on: per view counts, missing and failed shards, renderer
// mismatches, the reasons, whether a slower time only warns.
void read_verdict(const Reader& rd, const json& j, AuditDocument& d) {
  d.verdict = rd.text(j, "verdict", "");
  d.baseline_dir = rd.text(rd.at(j, "baseline", ""), "run_dir", "baseline");
  const json& views = rd.list(j, "views", "");
  for (std::size_t i = 0; i < views.size(); ++i) {
    const std::string at = "views[" + std::to_string(i) + "]";
    const json& v = views[i];
    d.views.push_back({rd.text(v, "platform", at), rd.text(v, "baseline_platform", at),
                       std::int64_t(rd.count(v, "compared", at)),
                       std::int64_t(rd.count(v, "changed", at)),
                       std::int64_t(rd.count(v, "flakes", at)),
                       std::int64_t(rd.count(v, "failed", at))});
  }
  const json& failures = rd.at(j, "failures", "");
  const json& missing = rd.list(failures, "missing_shards", "failures");
  for (std::size_t i = 0; i < missing.size(); ++i)
    d.missing_shard_platforms.push_back(
        rd.text(missing[i], "platform", "failures.missing_shards[" + std::to_string(i) + "]"));
  const json& manifest = rd.list(failures, "manifest", "failures");
  for (std::size_t i = 0; i < manifest.size(); ++i) {
    const std::string at = "failures.manifest[" + std::to_string(i) + "]";
    d.manifest_failures.push_back({rd.text(manifest[i], "platform", at),
                                   rd.text(manifest[i], "outcome", at)});
  }
  for (const json& m : rd.list(failures, "renderer_mismatches", "failures")) {
    if (!m.is_string()) rd.bad("failures.renderer_mismatches", "must be a list of strings");
    d.renderer_mismatches.push_back(m.get<std::string>());
  }
  for (const json& r : rd.list(j, "reasons", "")) {
    if (!r.is_string()) rd.bad("reasons", "must be a list of strings");
    d.reasons.push_back(r.get<std::string>());
  }
  const json& measured = rd.at(j, "speed_measurement", "");
  if (measured.is_object() && measured.contains("warn_only")) {
    if (!measured.at("warn_only").is_boolean())
      rd.bad("speed_measurement.warn_only", "must be true or false");
    d.speed_warn_only = measured.at("warn_only").get<bool>();
  }
}

}  // namespace

std::size_t AuditDocument::time_moved() const {
  std::size_t n = 0;
  for (const AuditedTime& t : speed) n += t.verdict == "faster" || t.verdict == "slower";
  return n;
}

bool AuditDocument::compares(const std::string& baseline, const std::string& current) const {
  for (const AuditedPair& p : pairs)
    if (p.baseline == baseline && p.current == current) return true;
  return false;
}

AuditDocument read_audit_document(const std::string& audit_dir) {
  AuditDocument d;
  d.path = run_folder::audit_json(audit_dir);
  json j;
  try {
    j = util::parse_json_document(util::read_file(d.path), d.path);
  } catch (const util::UserError&) {
    throw;
  } catch (const std::exception& e) {
    throw util::UserError(d.path + ": cannot read the audit (" + e.what() + ")");
  }
  require_document_header(j, kAuditDocument, kAuditDocumentVersion, d.path,
                                  "run the audit again with this renderaudit");
  const Reader rd{d.path};
  read_verdict(rd, j, d);
  const json& pairs = rd.list(j, "pairs", "");
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const std::string at = "pairs[" + std::to_string(i) + "]";
    d.pairs.push_back({rd.text(pairs[i], "baseline_platform", at),
                       rd.text(pairs[i], "current_platform", at)});
  }
  const json& counts = rd.at(j, "counts", "");
  d.compared = rd.count(counts, "compared", "counts");
  d.changed = rd.count(counts, "changed", "counts");
  d.new_violations = rd.count(counts, "new_violations", "counts");
  const json& tests = rd.at(j, "distribution_tests", "");
  d.significant_tests = rd.count(tests, "significant", "distribution_tests");
  d.family_size = rd.count(tests, "family_size", "distribution_tests");
  const json& measured = rd.at(j, "speed_measurement", "");
  const json& performed = rd.at(measured, "performed", "speed_measurement");
  if (!performed.is_boolean()) rd.bad("speed_measurement.performed", "must be true or false");
  d.timed = performed.get<bool>();
  const json& speed = rd.list(j, "speed", "");
  for (std::size_t i = 0; i < speed.size(); ++i) {
    const std::string at = "speed[" + std::to_string(i) + "]";
    const json& s = speed[i];
    d.speed.push_back({rd.text(s, "baseline_platform", at), rd.text(s, "platform", at),
                       rd.text(s, "kind", at), rd.text(s, "group", at), rd.text(s, "verdict", at),
                       rd.ratio(s, "ratio", at), rd.ratio(s, "low", at), rd.ratio(s, "high", at)});
  }
  const json& flakes = rd.at(j, "flakes", "");
  d.flakes_total = rd.count(flakes, "total", "flakes");
  const json& items = rd.list(flakes, "items", "flakes");
  for (std::size_t i = 0; i < items.size(); ++i) {
    const std::string at = "flakes.items[" + std::to_string(i) + "]";
    const json& f = items[i];
    d.flakes.push_back({rd.text(f, "baseline_platform", at), rd.text(f, "platform", at),
                        rd.text(f, "kind", at), int(rd.count(f, "view", at)),
                        rd.count(f, "index", at)});
  }
  return d;
}

}  // namespace ra::rundir
