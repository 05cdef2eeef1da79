// Writing and reading OUT/bisect.json (see the header).
#include "triage/bisect_state.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "analysis/view_equivalence.h"
#include "rundir/manifest.h"
#include "util/atomic_file.h"
#include "util/errors.h"
#include "util/git_ref_check.h"
#include "util/json_seal.h"
#include "util/json_file.h"

namespace ra::triage {
namespace {

nlohmann::json drawing_json(const Drawing& d) {
  nlohmann::json j = {{"error", d.error}, {"primitives", nlohmann::json::object()}};
  for (const auto& [label, hash] : d.hashes)
    j["primitives"][label] = {{"pixel_hash", std::to_string(hash)},
                              {"pixels", d.pixels.count(label) ? d.pixels.at(label) : -1}};
  return j;
}

// A number that may be undefined (no interval): null in JSON.
nlohmann::json maybe(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

nlohmann::json step_time_json(const StepTime& t) {
  return {{"kind", geometry::kind_name(t.group.kind)},
          {"view_group", t.group.view_group},
          {"place", time_place_name(t.place)},
          {"ratio", maybe(t.ratio)},
          {"low", maybe(t.low)},
          {"high", maybe(t.high)},
          {"share", maybe(t.share)},
          {"share_low", maybe(t.share_low)},
          {"share_high", maybe(t.share_high)},
          {"repeats", t.repeats},
          {"note", t.note}};
}

nlohmann::json comparison_json(const audit::SpeedComparison& c) {
  return {{"n", c.n},
          {"repeats", c.repeats},
          {"baseline_median_us", maybe(c.baseline_median_us)},
          {"current_median_us", maybe(c.current_median_us)},
          {"ratio", maybe(c.ratio)},
          {"low", maybe(c.low)},
          {"high", maybe(c.high)},
          {"control_ratio", maybe(c.control_ratio)},
          {"control_low", maybe(c.control_low)},
          {"control_high", maybe(c.control_high)},
          {"band", maybe(c.band)},
          {"verdict", audit::speed_verdict_name(c.verdict)},
          {"repeats_to_settle", c.repeats_to_settle},
          {"reason", c.reason}};
}

nlohmann::json step_json(const BisectStep& s) {
  nlohmann::json speed = nlohmann::json::array();
  for (const StepTime& t : s.speed) speed.push_back(step_time_json(t));
  return {{"role", s.role},       {"commit", s.commit},     {"subject", s.subject},
          {"date", s.date},       {"version", s.version},   {"position", s.position},
          {"error", s.error},     {"summary", s.summary},   {"build", s.build},
          {"build_dir", s.build_dir}, {"reused", s.reused}, {"build_s", s.build_s},
          {"draw_s", s.draw_s},   {"drawing", drawing_json(s.drawing)},
          {"speed", speed},       {"time_s", s.time_s}};
}

nlohmann::json round_json(const BisectRound& r) {
  return {{"round", r.round},           {"ways", r.ways},
          {"where", r.where},           {"commits", r.commits},
          {"failed", r.failed},         {"cancelled", r.cancelled},
          {"unresolved", r.unresolved}, {"rounds_to_go", r.rounds_to_go},
          {"build_wall_s", r.build_wall_s}, {"seconds", r.seconds},
          {"finished", r.finished}};
}

// Field readers that name the file and the key of what is wrong.
class Reader {
 public:
  explicit Reader(std::string path) : path_(std::move(path)) {}

  [[noreturn]] void bad(const std::string& key, const std::string& what) const {
    throw util::UserError("bisect: " + path_ + ": '" + key + "' " + what +
                          "; move the file away to start the bisection again");
  }
  const nlohmann::json& at(const nlohmann::json& j, const std::string& parent,
                           const std::string& key) const {
    if (!j.is_object()) bad(parent.empty() ? "(top)" : parent, "must be an object");
    const auto it = j.find(key);
    if (it == j.end()) bad(name(parent, key), "is missing");
    return *it;
  }
  std::string text(const nlohmann::json& j, const std::string& parent, const std::string& key) const {
    const nlohmann::json& v = at(j, parent, key);
    if (!v.is_string()) bad(name(parent, key), "must be a string");
    return v.get<std::string>();
  }
  double number(const nlohmann::json& j, const std::string& parent, const std::string& key) const {
    const nlohmann::json& v = at(j, parent, key);
    if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < 0)
      bad(name(parent, key), "must be a number of 0 or more");
    return v.get<double>();
  }
  std::size_t count(const nlohmann::json& j, const std::string& parent, const std::string& key) const {
    const nlohmann::json& v = at(j, parent, key);
    if (!v.is_number_unsigned()) bad(name(parent, key), "must be a whole number of 0 or more");
    return v.get<std::size_t>();
  }
  bool flag(const nlohmann::json& j, const std::string& parent, const std::string& key) const {
    const nlohmann::json& v = at(j, parent, key);
    if (!v.is_boolean()) bad(name(parent, key), "must be true or false");
    return v.get<bool>();
  }
  // A number or null (undefined: NaN).
  double maybe_number(const nlohmann::json& j, const std::string& parent,
                      const std::string& key) const {
    const nlohmann::json& v = at(j, parent, key);
    if (v.is_null()) return std::numeric_limits<double>::quiet_NaN();
    if (!v.is_number() || !std::isfinite(v.get<double>()))
      bad(name(parent, key), "must be a number or null");
    return v.get<double>();
  }
  int integer(const nlohmann::json& j, const std::string& parent, const std::string& key,
              int lo, int hi) const {
    const nlohmann::json& v = at(j, parent, key);
    if (!v.is_number_integer() || v.get<int64_t>() < lo || v.get<int64_t>() > hi)
      bad(name(parent, key), "must be a whole number from " + std::to_string(lo) + " to " +
                                 std::to_string(hi));
    return int(v.get<int64_t>());
  }
  SpeedGroup group(const nlohmann::json& j, const std::string& key) const {
    SpeedGroup g;
    if (!geometry::parse_kind(text(j, key, "kind"), &g.kind))
      bad(name(key, "kind"), "must be point, line or triangle");
    g.view_group = integer(j, key, "view_group", 0, 25);
    return g;
  }
  StepTime step_time(const nlohmann::json& j, const std::string& key) const {
    StepTime t;
    t.group = group(j, key);
    try {
      t.place = parse_time_place(text(j, key, "place"));
    } catch (const std::invalid_argument&) {
      bad(name(key, "place"), "must be \"as good\", \"as bad\" or \"unknown\"");
    }
    t.ratio = maybe_number(j, key, "ratio");
    t.low = maybe_number(j, key, "low");
    t.high = maybe_number(j, key, "high");
    t.share = maybe_number(j, key, "share");
    t.share_low = maybe_number(j, key, "share_low");
    t.share_high = maybe_number(j, key, "share_high");
    t.repeats = integer(j, key, "repeats", 0, 100000);
    t.note = text(j, key, "note");
    return t;
  }
  audit::SpeedComparison comparison(const nlohmann::json& j, const std::string& key) const {
    audit::SpeedComparison c;
    c.n = count(j, key, "n");
    c.repeats = integer(j, key, "repeats", 0, 100000);
    c.baseline_median_us = maybe_number(j, key, "baseline_median_us");
    c.current_median_us = maybe_number(j, key, "current_median_us");
    c.ratio = maybe_number(j, key, "ratio");
    c.low = maybe_number(j, key, "low");
    c.high = maybe_number(j, key, "high");
    c.control_ratio = maybe_number(j, key, "control_ratio");
    c.control_low = maybe_number(j, key, "control_low");
    c.control_high = maybe_number(j, key, "control_high");
    c.band = maybe_number(j, key, "band");
    const std::string verdict = text(j, key, "verdict");
    bool known = false;
    for (audit::SpeedVerdict v : {audit::SpeedVerdict::kSame, audit::SpeedVerdict::kFaster,
                                  audit::SpeedVerdict::kSlower, audit::SpeedVerdict::kUnknown})
      if (verdict == audit::speed_verdict_name(v)) c.verdict = v, known = true;
    if (!known) bad(name(key, "verdict"), "must be same, faster, slower or unknown");
    c.repeats_to_settle = integer(j, key, "repeats_to_settle", 0, 1000000);
    c.reason = text(j, key, "reason");
    return c;
  }
  static std::string name(const std::string& parent, const std::string& key) {
    return parent.empty() ? key : parent + "." + key;
  }

  Drawing drawing(const nlohmann::json& j, const std::string& key) const {
    Drawing d;
    d.error = text(j, key, "error");
    const nlohmann::json& prims = at(j, key, "primitives");
    if (!prims.is_object()) bad(name(key, "primitives"), "must be an object");
    for (const auto& [label, p] : prims.items()) {
      const std::string k = name(key, "primitives") + "[\"" + label + "\"]";
      const std::string hash = text(p, k, "pixel_hash");
      if (hash.empty() || hash.size() > 20 || hash.find_first_not_of("0123456789") != std::string::npos)
        bad(name(k, "pixel_hash"), "must be a decimal 64-bit number as text");
      try {
        d.hashes[label] = std::stoull(hash);
      } catch (const std::exception&) {
        bad(name(k, "pixel_hash"), "must be a decimal 64-bit number as text");
      }
      const nlohmann::json& px = at(p, k, "pixels");
      if (!px.is_number_integer()) bad(name(k, "pixels"), "must be a whole number");
      d.pixels[label] = px.get<int64_t>();
    }
    return d;
  }

  std::vector<std::string> commits(const nlohmann::json& j, const std::string& parent,
                                   const std::string& key) const {
    const nlohmann::json& v = at(j, parent, key);
    if (!v.is_array()) bad(name(parent, key), "must be an array");
    std::vector<std::string> out;
    for (std::size_t i = 0; i < v.size(); ++i) {
      const std::string k = name(parent, key) + "[" + std::to_string(i) + "]";
      if (!v[i].is_string() || !util::commit_hash_problem(v[i].get<std::string>()).empty())
        bad(k, "must be a full commit hash");
      out.push_back(v[i].get<std::string>());
    }
    return out;
  }

  BisectRound round(const nlohmann::json& j, const std::string& key) const {
    BisectRound r;
    r.round = count(j, key, "round");
    r.ways = count(j, key, "ways");
    r.where = text(j, key, "where");
    r.commits = commits(j, key, "commits");
    r.failed = commits(j, key, "failed");
    r.cancelled = commits(j, key, "cancelled");
    r.unresolved = count(j, key, "unresolved");
    r.rounds_to_go = count(j, key, "rounds_to_go");
    r.build_wall_s = number(j, key, "build_wall_s");
    r.seconds = number(j, key, "seconds");
    r.finished = flag(j, key, "finished");
    return r;
  }

  BisectStep step(const nlohmann::json& j, const std::string& key) const {
    BisectStep s;
    s.role = text(j, key, "role");
    const std::string role = key == "good" ? "good ref" : key == "bad" ? "bad ref" : "step";
    // An end not drawn yet is written with no role and no commit.
    if (s.role != role && !(role != "step" && s.role.empty()))
      bad(name(key, "role"), "must be \"" + role + "\"");
    s.commit = text(j, key, "commit");
    if (!s.commit.empty() && !util::commit_hash_problem(s.commit).empty())
      bad(name(key, "commit"), util::commit_hash_problem(s.commit) + " or empty");
    if (s.commit.empty() && role == "step") bad(name(key, "commit"), "must be a full commit hash");
    s.subject = text(j, key, "subject");
    s.date = text(j, key, "date");
    s.version = text(j, key, "version");
    s.position = count(j, key, "position");
    s.error = text(j, key, "error");
    s.summary = text(j, key, "summary");
    s.build = text(j, key, "build");
    s.build_dir = text(j, key, "build_dir");
    s.reused = flag(j, key, "reused");
    s.build_s = number(j, key, "build_s");
    s.draw_s = number(j, key, "draw_s");
    s.drawing = drawing(at(j, key, "drawing"), name(key, "drawing"));
    // Written by `bisect --speed` (absent from files of bisections of pixels only).
    if (j.contains("speed")) {
      const nlohmann::json& speed = at(j, key, "speed");
      if (!speed.is_array()) bad(name(key, "speed"), "must be an array");
      for (std::size_t i = 0; i < speed.size(); ++i)
        s.speed.push_back(step_time(speed[i], name(key, "speed") + "[" + std::to_string(i) + "]"));
      s.time_s = number(j, key, "time_s");
    }
    return s;
  }

 private:
  std::string path_;
};

}  // namespace

nlohmann::json bisect_state_json(const BisectState& st) {
  const BisectResult& r = st.result;
  nlohmann::json steps = nlohmann::json::array();
  for (const BisectStep& s : r.steps) steps.push_back(step_json(s));
  nlohmann::json rounds = nlohmann::json::array();
  for (const BisectRound& round : r.rounds) rounds.push_back(round_json(round));
  nlohmann::json selection = nlohmann::json::array();
  for (const BisectPrimitive& p : r.selection)
    selection.push_back({{"kind", geometry::kind_name(p.kind)}, {"view", p.view},
                         {"index", p.index}, {"view_group", p.view_group},
                         {"run_good_pixels", p.run_good_pixels},
                         {"run_bad_pixels", p.run_bad_pixels},
                         {"run_good_conformance", p.run_good_conformance},
                         {"run_bad_conformance", p.run_bad_conformance}});
  nlohmann::json culprits = nlohmann::json::array();
  for (const Culprit& c : r.culprits) {
    nlohmann::json prims = nlohmann::json::array();
    for (const std::string& l : c.primitives)
      prims.push_back({{"primitive", l},
                       {"pixels_before", c.pixels.at(l).first},
                       {"pixels_after", c.pixels.at(l).second}});
    culprits.push_back({{"commit", c.commit},
                        {"subject", c.subject},
                        {"date", c.date},
                        {"previous", c.previous},
                        {"merge", c.merge},
                        {"primitives", prims}});
  }
  nlohmann::json unattributed = nlohmann::json::array();
  for (const Unattributed& u : r.unattributed)
    unattributed.push_back({{"primitive", u.label},
                            {"from", u.from},
                            {"to", u.to},
                            {"candidates", u.candidates}});
  nlohmann::json speed_ends = nlohmann::json::array();
  for (const SpeedAtEnds& e : r.speed_ends) {
    nlohmann::json g = comparison_json(e.comparison);
    g["kind"] = geometry::kind_name(e.group.kind);
    g["view_group"] = e.group.view_group;
    g["group"] = analysis::view_group_label(e.group.view_group);
    speed_ends.push_back(g);
  }
  nlohmann::json speed_culprits = nlohmann::json::array();
  for (const SpeedCulprit& c : r.speed_culprits) {
    nlohmann::json parent_places = nlohmann::json::array();
    for (const StepTime& t : c.parent_places) parent_places.push_back(step_time_json(t));
    nlohmann::json moves = nlohmann::json::array();
    for (const SpeedCulprit::Move& m : c.moves) {
      nlohmann::json g = comparison_json(m.confirmation);
      g["kind"] = geometry::kind_name(m.group.kind);
      g["view_group"] = m.group.view_group;
      g["group"] = analysis::view_group_label(m.group.view_group);
      g["direction"] = audit::speed_verdict_name(m.direction);
      g["error"] = m.error;
      moves.push_back(g);
    }
    speed_culprits.push_back({{"commit", c.commit},
                              {"subject", c.subject},
                              {"date", c.date},
                              {"previous", c.previous},
                              {"confirmed_beside", c.beside},
                              {"confirmed_beside_note", c.beside_note},
                              {"parent_places", parent_places},
                              {"moves", moves}});
  }
  nlohmann::json speed_unattributed = nlohmann::json::array();
  for (const SpeedUnattributed& u : r.speed_unattributed)
    speed_unattributed.push_back({{"kind", geometry::kind_name(u.group.kind)},
                                  {"view_group", u.group.view_group},
                                  {"group", analysis::view_group_label(u.group.view_group)},
                                  {"from", u.from},
                                  {"to", u.to},
                                  {"candidates", u.candidates},
                                  {"why", u.why},
                                  {"next_command", u.next_command}});
  nlohmann::json j = {{"inputs", st.inputs},
                      {"original_head", r.original_head},
                      {"selection_rule", r.selection_rule},
                      {"changed_in_run", r.changed_in_run},
                      {"selection", selection},
                      {"dropped", r.dropped},
                      {"commits_in_range", r.commits_in_range},
                      {"good", step_json(r.good)},
                      {"bad", step_json(r.bad)},
                      {"steps", steps},
                      {"rounds", rounds},
                      {"culprits", culprits},
                      {"unattributed", unattributed},
                      {"speed_ends", speed_ends},
                      {"speed_culprits", speed_culprits},
                      {"speed_unattributed", speed_unattributed},
                      {"complete", r.complete()},
                      {"total_build_s", r.total_build_s}};
  j.update(rundir::document_header(rundir::kBisectionDocument, kBisectStateVersion, false));
  return util::sealed(j);
}

void save_bisect_state(const std::string& path, const BisectState& st) {
  util::write_file_atomic(path, bisect_state_json(st).dump(2) + "\n");
}

BisectState load_bisect_state(const std::string& path) {
  nlohmann::json j;
  try {
    j = util::parse_json_document(util::read_file(path), path);
  } catch (const std::exception& e) {
    throw util::UserError("bisect: " + path + " is not readable JSON (" + e.what() +
                          "); move it away to start the bisection again");
  }
  const Reader rd(path);
  BisectState st;
  // Version 2 was written before the seal: still read, each field checked on its own.
  const int version = rundir::bisection_version(j);
  if (version == 0)
    rd.bad("schema_version", "is not " + std::to_string(kBisectStateVersion) + " (or " +
                                 std::to_string(rundir::kUnsealedBisectionVersion) +
                                 ") of renderaudit-bisection: written by another "
                                 "renderaudit (a bisection of git bisect's kind)");
  if (const std::string problem = rundir::bisection_seal_problem(j, version); !problem.empty())
    throw util::UserError("bisect: " + path + ": " + problem +
                          "; move the file away to start the bisection again");
  st.inputs = rd.at(j, "", "inputs");
  if (!st.inputs.is_object()) rd.bad("inputs", "must be an object");
  st.result.original_head = rd.text(j, "", "original_head");
  // Checked out again after a kill -9: a branch or a commit, never something git reads as an
  // option (`--orphan=x`).
  const std::string& head = st.result.original_head;
  if (!head.empty() && !util::commit_hash_problem(head).empty() &&
      !util::branch_name_problem(head).empty())
    rd.bad("original_head", "must be the branch the tree was on or a full commit hash (" +
                                util::branch_name_problem(head) + ")");
  const nlohmann::json& steps = rd.at(j, "", "steps");
  if (!steps.is_array()) rd.bad("steps", "must be an array");
  for (std::size_t i = 0; i < steps.size(); ++i)
    st.result.steps.push_back(rd.step(steps[i], "steps[" + std::to_string(i) + "]"));
  // Written since builds at once (`--ways`); absent from older files.
  if (j.contains("rounds")) {
    const nlohmann::json& rounds = rd.at(j, "", "rounds");
    if (!rounds.is_array()) rd.bad("rounds", "must be an array");
    for (std::size_t i = 0; i < rounds.size(); ++i)
      st.result.rounds.push_back(rd.round(rounds[i], "rounds[" + std::to_string(i) + "]"));
  }
  if (j.contains("speed_ends")) {
    const nlohmann::json& ends = rd.at(j, "", "speed_ends");
    if (!ends.is_array()) rd.bad("speed_ends", "must be an array");
    for (std::size_t i = 0; i < ends.size(); ++i) {
      const std::string key = "speed_ends[" + std::to_string(i) + "]";
      SpeedAtEnds e{rd.group(ends[i], key), rd.comparison(ends[i], key)};
      e.comparison.kind = e.group.kind;
      e.comparison.view_group = e.group.view_group;
      e.comparison.group = analysis::view_group_label(e.group.view_group);
      st.result.speed_ends.push_back(e);
    }
  }
  for (const char* end : {"good", "bad"}) {
    const nlohmann::json& s = rd.at(j, "", end);
    BisectStep step = rd.step(s, end);
    (std::string(end) == "good" ? st.result.good : st.result.bad) = step;
  }
  return st;
}

}  // namespace ra::triage
