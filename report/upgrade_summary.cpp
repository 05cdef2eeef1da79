// The driver upgrade's summary document (see the header).
#include "report/upgrade_summary.h"

#include <algorithm>
#include <cmath>

#include "rundir/manifest.h"
#include "util/atomic_file.h"
#include "util/errors.h"
#include "util/json_number.h"

using nlohmann::json;

namespace ra::report {
namespace {

bool faster_or_slower(const UpgradeTime& t) {
  return t.verdict == "faster" || t.verdict == "slower";
}

// Field readers naming the file and the key of what is wrong.
const json& member(const json& j, const std::string& key, const std::string& where,
                   const std::string& path) {
  if (!j.is_object() || !j.contains(key))
    throw util::UserError(path + ": '" + where + key + "' is missing; write the summary again "
                          "with `renderaudit report RUN --upgrade BUILD`");
  return j.at(key);
}
std::string text_of(const json& j, const std::string& key, const std::string& where,
                    const std::string& path) {
  const json& v = member(j, key, where, path);
  if (!v.is_string()) throw util::UserError(path + ": '" + where + key + "' must be a string");
  return v.get<std::string>();
}
std::int64_t count_of(const json& j, const std::string& key, const std::string& where,
                      const std::string& path) {
  const json& v = member(j, key, where, path);
  if (!v.is_number_integer() || v.get<std::int64_t>() < 0)
    throw util::UserError(path + ": '" + where + key + "' must be a whole number of 0 or more");
  return v.get<std::int64_t>();
}

// A time ratio or an end of its interval: a number above 0, or null (NaN) where the audit formed
// none.
double ratio_of(const json& j, const std::string& key, const std::string& where,
                const std::string& path) {
  const json& v = member(j, key, where, path);
  if (v.is_null()) return NAN;
  if (!v.is_number() || !(v.get<double>() > 0) || !std::isfinite(v.get<double>()))
    throw util::UserError(path + ": '" + where + key +
                          "' must be a number above 0, or null where no interval was formed");
  return v.get<double>();
}

// One group's drawing time; a faster or slower verdict needs its numbers, on its side of 1.
UpgradeTime time_of(const json& j, const std::string& at, const std::string& path) {
  UpgradeTime t{text_of(j, "kind", at, path),   text_of(j, "group", at, path),
                ratio_of(j, "ratio", at, path), ratio_of(j, "low", at, path),
                ratio_of(j, "high", at, path),  text_of(j, "verdict", at, path)};
  if (t.verdict != "faster" && t.verdict != "slower" && t.verdict != "same" &&
      t.verdict != "unknown")
    throw util::UserError(path + ": '" + at + "verdict' is '" + t.verdict +
                          "' (allowed: faster, slower, same, unknown)");
  if (!faster_or_slower(t)) return t;
  const auto bad = [&](const std::string& what) {
    throw util::UserError(path + ": '" + at + what + " for a '" + t.verdict +
                          "' verdict; write the summary again with `renderaudit report RUN --upgrade BUILD`");
  };
  if (std::isnan(t.ratio) || std::isnan(t.low) || std::isnan(t.high))
    bad("ratio', 'low' and 'high' must be numbers");
  if (!(t.low <= t.ratio && t.ratio <= t.high))
    bad("low' <= 'ratio' <= 'high' does not hold (" + std::to_string(t.low) + ", " +
        std::to_string(t.ratio) + ", " + std::to_string(t.high) + ")");
  if (t.verdict == "faster" && !(t.high < 1))
    bad("high' (" + std::to_string(t.high) + ") must be below 1");
  if (t.verdict == "slower" && !(t.low > 1))
    bad("low' (" + std::to_string(t.low) + ") must be above 1");
  return t;
}

// The counts of a stratum are parts of one another (each changed primitive is counted once among
// not drawn / newly drawn and once among new violation / fixed / allowed / other), and every sum
// the sentence makes stays far from 2^63: each count is at most `compared`, whose total over the
// summary is kept under 2^62.
void check_stratum(const UpgradeStratum& s, const std::string& at, const std::string& path,
                   std::int64_t& total_compared) {
  const auto bad = [&](const std::string& what) {
    throw util::UserError(path + ": '" + at + what +
                          ": the counts do not add up; write the summary again with "
                          "`renderaudit report RUN --upgrade BUILD`");
  };
  if (s.changed > s.compared)
    bad("changed' (" + std::to_string(s.changed) + ") is more than 'compared' (" +
        std::to_string(s.compared) + ")");
  if (s.not_drawn > s.changed - s.newly_drawn)
    bad("not_drawn' (" + std::to_string(s.not_drawn) + ") and 'newly_drawn' (" +
        std::to_string(s.newly_drawn) + ") are more than 'changed' (" +
        std::to_string(s.changed) + ")");
  if (s.new_violations > s.changed || s.fixed_violations > s.changed - s.new_violations ||
      s.allowed > s.changed - s.new_violations - s.fixed_violations)
    bad("new_violations', 'fixed_violations' and 'allowed' (" +
        std::to_string(s.new_violations) + ", " + std::to_string(s.fixed_violations) + ", " +
        std::to_string(s.allowed) + ") are more than 'changed' (" + std::to_string(s.changed) +
        ")");
  // not drawn and breaking the rules: of both; the rest of the not drawn among the "more"
  if (s.not_drawn_violations >= 0 &&
      (s.not_drawn_violations > std::min(s.not_drawn, s.new_violations) ||
       s.not_drawn - s.not_drawn_violations >
           s.changed - s.new_violations - s.fixed_violations - s.allowed))
    bad("not_drawn_violations' (" + std::to_string(s.not_drawn_violations) +
        ") is more than 'not_drawn' (" + std::to_string(s.not_drawn) + ") or 'new_violations' (" +
        std::to_string(s.new_violations) + "), or leaves more not drawn than changed otherwise");
  constexpr std::int64_t kMost = std::int64_t(1) << 62;
  if (s.compared > kMost - total_compared)
    throw util::UserError(path + ": '" + at + "compared' (" + std::to_string(s.compared) +
                          ") takes the summary past 2^62 primitives, more than any run holds; "
                          "write the summary again with `renderaudit report RUN --upgrade BUILD`");
  total_compared += s.compared;
}

}  // namespace

json upgrade_summary_json(const UpgradeSummary& s) {
  json j = rundir::document_header("upgrade-summary", kUpgradeSummaryVersion, false);
  j["run"] = s.run_dir;
  j["build"] = s.build;
  json groups = json::array();
  for (const UpgradeViewGroup& g : s.groups)
    groups.push_back({{"label", g.label}, {"fov_deg", g.fov_deg}, {"window", g.window}});
  j["groups"] = groups;
  json pairs = json::array();
  for (const UpgradePair& p : s.pairs) {
    json strata = json::array();
    for (const UpgradeStratum& t : p.strata) {
      json stratum = {{"kind", t.kind},
                      {"group", t.group},
                      {"compared", t.compared},
                      {"changed", t.changed},
                      {"not_drawn", t.not_drawn},
                      {"newly_drawn", t.newly_drawn},
                      {"new_violations", t.new_violations},
                      {"fixed_violations", t.fixed_violations},
                      {"allowed", t.allowed}};
      if (t.not_drawn_violations >= 0) stratum["not_drawn_violations"] = t.not_drawn_violations;
      strata.push_back(stratum);
    }
    json pair = {{"platform", p.platform},
                 {"build_platform", p.build_platform},
                 {"installed_version", p.installed_version},
                 {"build_version", p.build_version},
                 {"fingerprint", p.fingerprint},
                 {"strata", strata}};
    if (p.timed) {
      json speed = json::array();
      for (const UpgradeTime& t : p.speed)
        speed.push_back({{"kind", t.kind},
                         {"group", t.group},
                         {"ratio", util::finite_or_null(t.ratio)},
                         {"low", util::finite_or_null(t.low)},
                         {"high", util::finite_or_null(t.high)},
                         {"verdict", t.verdict}});
      pair["speed"] = speed;
    }
    pairs.push_back(pair);
  }
  j["pairs"] = pairs;
  return j;
}

void write_upgrade_summary(const UpgradeSummary& summary, const std::string& path) {
  util::write_file_atomic(path, upgrade_summary_json(summary).dump(1) + "\n");
}

UpgradeSummary read_upgrade_summary(const std::string& path) {
  json j;
  try {
    j = json::parse(util::read_file(path));
  } catch (const std::exception& e) {
    throw util::UserError("cannot read the upgrade summary " + path + ": " + e.what());
  }
  rundir::require_document_header(j, "upgrade-summary", kUpgradeSummaryVersion, path,
                                  "written by `renderaudit report RUN --upgrade BUILD`");
  UpgradeSummary s;
  s.run_dir = text_of(j, "run", "", path);
  s.build = text_of(j, "build", "", path);
  const json& groups = member(j, "groups", "", path);
  if (!groups.is_array()) throw util::UserError(path + ": 'groups' must be a list");
  for (std::size_t i = 0; i < groups.size(); ++i) {
    const std::string at = "groups[" + std::to_string(i) + "].";
    s.groups.push_back({text_of(groups[i], "label", at, path),
                        int(count_of(groups[i], "fov_deg", at, path)),
                        int(count_of(groups[i], "window", at, path))});
  }
  const json& pairs = member(j, "pairs", "", path);
  if (!pairs.is_array()) throw util::UserError(path + ": 'pairs' must be a list");
  std::int64_t total_compared = 0;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const std::string at = "pairs[" + std::to_string(i) + "].";
    const json& p = pairs[i];
    UpgradePair pair{text_of(p, "platform", at, path),
                     text_of(p, "build_platform", at, path),
                     text_of(p, "installed_version", at, path),
                     text_of(p, "build_version", at, path),
                     text_of(p, "fingerprint", at, path),
                     {},
                     false,
                     {}};
    const json& strata = member(p, "strata", at, path);
    if (!strata.is_array()) throw util::UserError(path + ": '" + at + "strata' must be a list");
    for (std::size_t k = 0; k < strata.size(); ++k) {
      const std::string sat = at + "strata[" + std::to_string(k) + "].";
      const json& t = strata[k];
      pair.strata.push_back({text_of(t, "kind", sat, path), text_of(t, "group", sat, path),
                             count_of(t, "compared", sat, path), count_of(t, "changed", sat, path),
                             count_of(t, "not_drawn", sat, path),
                             count_of(t, "newly_drawn", sat, path),
                             count_of(t, "new_violations", sat, path),
                             count_of(t, "fixed_violations", sat, path),
                             count_of(t, "allowed", sat, path)});
      // optional: absent from a summary written before it was kept
      if (t.is_object() && t.contains("not_drawn_violations"))
        pair.strata.back().not_drawn_violations = count_of(t, "not_drawn_violations", sat, path);
      check_stratum(pair.strata.back(), sat, path, total_compared);
    }
    // optional: absent where the audit did not judge drawing time
    if (p.contains("speed")) {
      const json& speed = p.at("speed");
      if (!speed.is_array()) throw util::UserError(path + ": '" + at + "speed' must be a list");
      pair.timed = true;
      for (std::size_t k = 0; k < speed.size(); ++k)
        pair.speed.push_back(time_of(speed[k], at + "speed[" + std::to_string(k) + "].", path));
    }
    s.pairs.push_back(std::move(pair));
  }
  return s;
}

}  // namespace ra::report
