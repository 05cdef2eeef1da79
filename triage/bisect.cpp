// The bisection loop (see the header).
#include "triage/bisect.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "audit/audit_compare.h"
#include "triage/bisect_report.h"
#include "audit/flake_check.h"
#include "rundir/platform_spec.h"
#include "rundir/experiment.h"
#include "rundir/manifest.h"
#include "util/atomic_file.h"
#include "util/child_process.h"
#include "util/duration_text.h"
#include "util/errors.h"

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace ra::triage {
namespace {


struct GitResult {
  bool ok = false;
  std::string out;
};

GitResult git(const std::string& dir, std::vector<std::string> args) {
  args.insert(args.begin(), {"git", "-C", dir, "-c", "advice.detachedHead=false"});
  util::ChildSpec spec;
  spec.argv = args;
  spec.stdin_null = true;
  spec.capture_output = true;
  const util::ProgramResult r = util::run_program(spec);
  GitResult g{r.exited_ok(), r.output};
  while (!g.out.empty() && (g.out.back() == '\n' || g.out.back() == ' ')) g.out.pop_back();
  return g;
}

std::string git_ok(const std::string& dir, const std::vector<std::string>& args,
                   const std::string& what) {
  const GitResult g = git(dir, args);
  if (!g.ok) throw util::UserError("bisect: " + what + " failed in " + dir + ":\n" + g.out);
  return g.out;
}

std::string rev(const std::string& dir, const std::string& ref) {
  const GitResult g = git(dir, {"rev-parse", "--verify", "--quiet", ref + "^{commit}"});
  if (!g.ok || g.out.empty())
    throw util::UserError("bisect: '" + ref + "' is not a commit of " + dir);
  return g.out;
}

// subject, date (ISO), VERSION file of a commit
void describe_commit(const std::string& dir, BisectStep& s) {
  const std::string info = git(dir, {"log", "-1", "--format=%cI%n%s", s.commit}).out;
  s.date = info.substr(0, info.find('\n'));
  s.subject = info.find('\n') == std::string::npos ? "" : info.substr(info.find('\n') + 1);
  const GitResult v = git(dir, {"show", s.commit + ":VERSION"});
  s.version = v.ok ? v.out : "";
}

std::string short_hash(const std::string& c) { return c.substr(0, 12); }

// j[key], or null when absent (no temporary default object to iterate).
const nlohmann::json& member(const nlohmann::json& j, const char* key) {
  static const nlohmann::json none;
  const auto it = j.find(key);
  return it == j.end() ? none : *it;
}

nlohmann::json drawing_json(const Drawing& d) {
  nlohmann::json j = {{"error", d.error}, {"primitives", nlohmann::json::object()}};
  for (const auto& [label, hash] : d.hashes)
    j["primitives"][label] = {{"pixel_hash", std::to_string(hash)},
                              {"pixels", d.pixels.count(label) ? d.pixels.at(label) : -1}};
  return j;
}

Drawing drawing_from_json(const nlohmann::json& j) {
  Drawing d;
  d.error = j.value("error", "");
  const nlohmann::json& prims = member(j, "primitives");
  if (!prims.is_object()) return d;
  for (const auto& [label, p] : prims.items()) {
    d.hashes[label] = std::stoull(p.value("pixel_hash", "0"));
    d.pixels[label] = p.value("pixels", int64_t(-1));
  }
  return d;
}

StepVerdict verdict_of(const std::string& s) {
  return s == "good" ? StepVerdict::kGood : s == "bad" ? StepVerdict::kBad : StepVerdict::kSkip;
}

nlohmann::json step_json(const BisectStep& s) {
  return {{"role", s.role},       {"commit", s.commit},   {"subject", s.subject},
          {"date", s.date},       {"version", s.version}, {"verdict", verdict_name(s.verdict)},
          {"reason", s.reason},   {"build", s.build},     {"build_dir", s.build_dir},
          {"reused", s.reused},   {"build_s", s.build_s}, {"draw_s", s.draw_s},
          {"drawing", drawing_json(s.drawing)}};
}

BisectStep step_from_json(const nlohmann::json& j) {
  BisectStep s;
  s.role = j.value("role", "");
  s.commit = j.value("commit", "");
  s.subject = j.value("subject", "");
  s.date = j.value("date", "");
  s.version = j.value("version", "");
  s.verdict = verdict_of(j.value("verdict", "skip"));
  s.reason = j.value("reason", "");
  s.build = j.value("build", "");
  s.build_dir = j.value("build_dir", "");
  s.reused = j.value("reused", false);
  s.build_s = j.value("build_s", 0.0);
  s.draw_s = j.value("draw_s", 0.0);
  s.drawing = drawing_from_json(member(j, "drawing"));
  return s;
}

// The run's changed primitives between the two platforms, largest pixel change first.
std::vector<BisectPrimitive> select_from_run(const BisectOptions& o) {
  std::vector<BisectPrimitive> out;
  if (!o.primitives.empty()) {
    for (const std::string& p : o.primitives) out.push_back(parse_primitive(p));
    return out;
  }
  if (o.good_platform.empty() || o.bad_platform.empty())
    throw util::UserError(
        "bisect: name the two platforms of the run whose records differ (--between GOOD BAD), "
        "or the primitives (--primitive KIND:VIEW:INDEX)");
  const audit::PrimitiveComparison c =
      audit::compare_primitives(o.run_dir, o.run_dir, {{o.good_platform, o.bad_platform}});
  for (const audit::ChangedPrimitive& ch : c.changed) {
    if (!o.kinds.empty() &&
        std::find(o.kinds.begin(), o.kinds.end(), geometry::kind_name(ch.kind)) == o.kinds.end())
      continue;
    if (!o.views.empty() && std::find(o.views.begin(), o.views.end(), ch.view) == o.views.end())
      continue;
    if (ch.before.pixel_hash == ch.after.pixel_hash) continue;  // a verdict change only
    out.push_back({ch.kind, ch.view, ch.index, ch.before.pixels, ch.after.pixels});
  }
  std::stable_sort(out.begin(), out.end(), [](const BisectPrimitive& a, const BisectPrimitive& b) {
    return std::llabs(a.run_bad_pixels - a.run_good_pixels) >
           std::llabs(b.run_bad_pixels - b.run_good_pixels);
  });
  if (out.size() > o.max_primitives) out.resize(o.max_primitives);
  if (out.empty())
    throw util::UserError("bisect: no primitive of " + o.run_dir + " has other pixels on " +
                          o.bad_platform + " than on " + o.good_platform +
                          " (with the --kind/--view filters): nothing to bisect");
  return out;
}

}  // namespace

std::string bisect_step_experiment(const std::string& run_dir, const std::string& build_dir) {
  std::string text = util::read_file(run_dir + "/experiment.toml");
  if (!text.empty() && text.back() != '\n') text += '\n';
  nlohmann::json dir = build_dir;  // a JSON string is a valid TOML basic string
  return text + "\n[builds." + kStepBuild + "]   # added by renderaudit bisect\ndir = " +
         dir.dump() + "\n";
}

namespace {

Drawing draw_selection(const BisectOptions& o, const std::string& platform,
                       const std::vector<BisectPrimitive>& selection, const std::string& build_dir) {
  std::vector<audit::RerenderRequest> requests;
  const std::string qualified = platform + "@" + kStepBuild;
  for (const BisectPrimitive& p : selection) requests.push_back({qualified, p.kind, p.view, p.index});
  audit::RerenderOptions ro;
  ro.run_dir = o.run_dir;
  ro.jobs = o.jobs;
  ro.attempt = 1;
  ro.experiment_text = bisect_step_experiment(o.run_dir, build_dir);
  ro.copy_driver_files = false;  // another driver than the run's, by design
  const audit::RerenderResult r = audit::rerender(audit::plan_rerender(requests, {}, 500), ro);
  Drawing d;
  for (const audit::RerenderBatch& b : r.batches)
    if (!b.error.empty() && d.error.empty())
      d.error = std::string(geometry::kind_name(b.kind)) + "s " + std::to_string(b.begin) + "-" +
                std::to_string(b.end - 1) + " of view " + std::to_string(b.view) + ": " + b.error;
  for (const BisectPrimitive& p : selection) {
    const auto key = std::tuple{qualified, int(p.kind), p.view, p.index};
    if (const auto it = r.hashes.find(key); it != r.hashes.end()) {
      d.hashes[p.label()] = it->second;
      d.pixels[p.label()] = r.pixels.at(key);
    }
  }
  return d;
}

struct State {
  std::string path;
  nlohmann::json inputs;
  BisectResult result;
  void save() const {
    nlohmann::json steps = nlohmann::json::array();
    for (const BisectStep& s : result.steps) steps.push_back(step_json(s));
    nlohmann::json selection = nlohmann::json::array();
    for (const BisectPrimitive& p : result.selection)
      selection.push_back({{"kind", geometry::kind_name(p.kind)}, {"view", p.view},
                           {"index", p.index}, {"run_good_pixels", p.run_good_pixels},
                           {"run_bad_pixels", p.run_bad_pixels}});
    nlohmann::json confirm = nlohmann::json::object();
    for (const auto& [k, s] : result.confirm) confirm[k] = step_json(s);
    nlohmann::json j = {{"inputs", inputs},
                        {"selection", selection},
                        {"dropped", result.dropped},
                        {"good", step_json(result.good)},
                        {"bad", step_json(result.bad)},
                        {"steps", steps},
                        {"found", result.found},
                        {"first_bad", result.first_bad},
                        {"first_bad_subject", result.first_bad_subject},
                        {"first_bad_date", result.first_bad_date},
                        {"parent", result.parent},
                        {"candidates", result.candidates},
                        {"confirm", confirm},
                        {"total_build_s", result.total_build_s}};
    j.update(rundir::document_header("bisection", 1, false));
    util::write_file_atomic(path, j.dump(2) + "\n");
  }
};

// What git says after `git bisect start/good/bad/skip`.
struct GitBisectState {
  bool done = false, ambiguous = false;
  std::string first_bad;
  std::vector<std::string> candidates;
  int steps_left = -1;  // "roughly N steps"
};

// `git bisect VERB ...`: git exits non-zero when only skipped commits are left, which is an answer.
std::string git_bisect(const std::string& dir, const std::vector<std::string>& args) {
  std::vector<std::string> a = {"bisect"};
  a.insert(a.end(), args.begin(), args.end());
  const GitResult g = git(dir, a);
  if (!g.ok && g.out.find("only 'skip'ped commits left") == std::string::npos)
    throw util::UserError("bisect: git bisect " + args.front() + " failed in " + dir + ":\n" + g.out);
  return g.out;
}

GitBisectState parse_bisect_output(const std::string& out) {
  GitBisectState s;
  if (const auto at = out.find(" is the first bad commit"); at != std::string::npos) {
    s.done = true;
    const auto line = out.rfind('\n', at);
    s.first_bad = out.substr(line == std::string::npos ? 0 : line + 1,
                             at - (line == std::string::npos ? 0 : line + 1));
    return s;
  }
  if (out.find("only 'skip'ped commits left") != std::string::npos) {
    s.done = s.ambiguous = true;
    std::istringstream in(out);
    for (std::string l; std::getline(in, l);)
      if (l.size() >= 40 && l.find_first_not_of("0123456789abcdef") >= 40)
        s.candidates.push_back(l.substr(0, 40));
    return s;
  }
  if (const auto at = out.find("(roughly "); at != std::string::npos)
    s.steps_left = std::atoi(out.c_str() + at + 9);
  return s;
}

}  // namespace

std::string BisectPrimitive::label() const {
  return std::string(geometry::kind_name(kind)) + " " + std::to_string(index) + " of view " +
         std::to_string(view);
}

const char* verdict_name(StepVerdict v) {
  return v == StepVerdict::kGood ? "good" : v == StepVerdict::kBad ? "bad" : "skip";
}

BisectPrimitive parse_primitive(const std::string& text) {
  BisectPrimitive p;
  const auto a = text.find(':'), b = text.rfind(':');
  char* end = nullptr;
  bool ok = a != std::string::npos && b != a && geometry::parse_kind(text.substr(0, a), &p.kind);
  if (ok) {
    const std::string v = text.substr(a + 1, b - a - 1), i = text.substr(b + 1);
    const long view = std::strtol(v.c_str(), &end, 10);
    ok = !v.empty() && *end == 0 && view >= 1 && view <= 1000;
    p.view = int(view);
    ok = ok && !i.empty() && i.find_first_not_of("0123456789") == std::string::npos && i.size() < 19;
    if (ok) p.index = std::stoull(i);
  }
  if (!ok)
    throw util::UserError("bisect: --primitive '" + text +
                          "' must be KIND:VIEW:INDEX (KIND point, line or triangle; VIEW 1-based; "
                          "INDEX a primitive index, e.g. line:5:721)");
  return p;
}

std::pair<StepVerdict, std::string> judge_drawing(const std::vector<BisectPrimitive>& selection,
                                              const Drawing& d, const Drawing& good,
                                              const Drawing& bad) {
  if (!d.error.empty()) return {StepVerdict::kSkip, "drawing failed: " + d.error};
  std::size_t like_good = 0, like_bad = 0;
  std::vector<std::string> neither;
  for (const BisectPrimitive& p : selection) {
    const std::string l = p.label();
    const auto it = d.hashes.find(l);
    if (it == d.hashes.end()) {
      neither.push_back(l + ": not drawn");
      continue;
    }
    if (good.hashes.count(l) && it->second == good.hashes.at(l)) {
      ++like_good;
    } else if (bad.hashes.count(l) && it->second == bad.hashes.at(l)) {
      ++like_bad;
    } else {
      neither.push_back(l + ": " + std::to_string(d.pixels.at(l)) + " pixels (good ref " +
                        std::to_string(good.pixels.count(l) ? good.pixels.at(l) : -1) +
                        ", bad ref " + std::to_string(bad.pixels.count(l) ? bad.pixels.at(l) : -1) +
                        ")");
    }
  }
  const std::size_t n = selection.size();
  if (like_good == n) return {StepVerdict::kGood, "all " + std::to_string(n) + " like the good ref"};
  if (like_bad == n) return {StepVerdict::kBad, "all " + std::to_string(n) + " like the bad ref"};
  std::string why = "pixels are neither: " + std::to_string(like_good) + " like the good ref, " +
                    std::to_string(like_bad) + " like the bad ref, " +
                    std::to_string(neither.size()) + " like neither";
  for (std::size_t i = 0; i < neither.size() && i < 3; ++i) why += (i ? "; " : " (") + neither[i];
  if (!neither.empty()) why += neither.size() > 3 ? "; ...)" : ")";
  return {StepVerdict::kSkip, why};
}

namespace {

// One invocation of the bisection: its inputs checked, its state, and the steps of the loop.
class Bisection {
 public:
  Bisection(const BisectOptions& options, const std::function<void(const std::string&)>& progress)
      : o_(options), progress_(progress) {}

  BisectResult run() {
    const auto t_start = Clock::now();
    check_inputs();
    load_state();
    draw_references();
    GitBisectState gs = bisect();
    if (gs.ambiguous) {
      st_.result.candidates = gs.candidates;
      say("skipped commits leave " + std::to_string(gs.candidates.size()) +
          " candidates for the first bad commit");
    } else {
      confirm(gs.first_bad);
    }
    BisectResult& r = st_.result;
    r.total_build_s = r.good.build_s + r.bad.build_s;
    for (const BisectStep& s : r.steps) r.total_build_s += s.build_s;
    for (const auto& [k, s] : r.confirm) r.total_build_s += s.build_s;
    r.seconds = std::chrono::duration<double>(Clock::now() - t_start).count();
    st_.save();
    r.report_path = o_.out_dir + "/bisect.md";
    write_bisect_report(o_, r, judged_, progress_ ? progress_ : [](const std::string&) {});
    return r;
  }

 private:
  void say(const std::string& s) const {
    if (progress_) progress_(s);
  }

  void check_inputs() {
    std::error_code ec;
    if (!fs::exists(o_.run_dir + "/experiment.toml", ec))
      throw util::UserError("bisect: " + o_.run_dir + " is not a run directory (no experiment.toml)");
    if (o_.source.empty() || !fs::is_directory(o_.source, ec))
      throw util::UserError("bisect: --source '" + o_.source + "' is not a folder");
    o_.source = fs::canonical(o_.source).string();
    if (!git(o_.source, {"rev-parse", "--git-dir"}).ok)
      throw util::UserError("bisect: " + o_.source + " is not a git checkout");
    if (!git(o_.source, {"status", "--porcelain", "--untracked-files=no"}).out.empty())
      throw util::UserError("bisect: " + o_.source +
                            " has uncommitted changes; commit or stash them first (each step "
                            "checks out another commit)");
    git_dir_ = git_ok(o_.source, {"rev-parse", "--absolute-git-dir"}, "git rev-parse");
    good_ = rev(o_.source, o_.good_ref);
    bad_ = rev(o_.source, o_.bad_ref);
    if (!git(o_.source, {"merge-base", "--is-ancestor", good_, bad_}).ok)
      throw util::UserError("bisect: the good ref " + o_.good_ref +
                            " is not an ancestor of the bad ref " + o_.bad_ref + " in " + o_.source);
    if (o_.platform.empty()) o_.platform = rundir::split_build(o_.bad_platform).first;
    if (o_.platform.empty())
      throw util::UserError("bisect: name the platform that draws each build (--platform, e.g. "
                            "egl-llvmpipe)");
    if (!rundir::find_platform(o_.platform + "@" + kStepBuild))
      throw util::UserError("bisect: platform '" + o_.platform +
                            "' cannot draw with a driver build (allowed: the osmesa-* and "
                            "surfaceless egl-* platforms, vk-lavapipe, faulty)");
    if (o_.out_dir.empty()) o_.out_dir = o_.run_dir + "/bisect";
    fs::create_directories(o_.out_dir, ec);
    if (ec) throw util::UserError(util::io_error_message("cannot create", o_.out_dir));
  }

  // The selection, and the steps of an earlier invocation with the same inputs.
  void load_state() {
    st_.path = o_.out_dir + "/bisect.json";
    st_.result.json_path = st_.path;
    st_.result.selection = select_from_run(o_);
    nlohmann::json selection_ids = nlohmann::json::array();
    for (const BisectPrimitive& p : st_.result.selection) selection_ids.push_back(p.label());
    st_.inputs = {{"run", fs::weakly_canonical(o_.run_dir).string()},
                  {"source", o_.source},
                  {"good", good_},
                  {"bad", bad_},
                  {"paths", o_.paths},
                  {"platform", o_.platform},
                  {"good_platform", o_.good_platform},
                  {"bad_platform", o_.bad_platform},
                  {"selection", selection_ids},
                  {"llvm_config", o_.build.llvm_config},
                  {"meson_options", o_.build.meson_options},
                  {"build_command", o_.build.build_command}};
    std::error_code ec;
    if (!fs::exists(st_.path, ec)) return;
    nlohmann::json old;
    try {
      old = nlohmann::json::parse(util::read_file(st_.path));
    } catch (const std::exception& e) {
      throw util::UserError("bisect: " + st_.path + " is not readable (" + e.what() +
                            "); move it away to start again");
    }
    for (const auto& [k, v] : st_.inputs.items())
      if (!member(old, "inputs").is_object() || member(member(old, "inputs"), k.c_str()) != v)
        throw util::UserError("bisect: " + st_.path + " holds a bisection of other inputs ('" + k +
                              "' differs); choose another --out, or remove it to start again");
    if (member(old, "steps").is_array())
      for (const auto& s : member(old, "steps")) st_.result.steps.push_back(step_from_json(s));
    if (old.contains("good")) st_.result.good = step_from_json(old["good"]);
    if (old.contains("bad")) st_.result.bad = step_from_json(old["bad"]);
    if (member(old, "confirm").is_object())
      for (const auto& [k, s] : member(old, "confirm").items())
        st_.result.confirm[k] = step_from_json(s);
    say("resuming " + st_.path + ": " + std::to_string(st_.result.steps.size()) + " steps judged");
  }

  // Builds and draws one commit (`ref` checked out by builds build; "" as checked out now).
  void evaluate(BisectStep& s, const std::string& ref) {
    describe_commit(o_.source, s);
    runner::SourceBuildOptions b = o_.build;
    b.source = o_.source;
    b.ref = ref;
    b.probe = false;  // the drawing is the probe
    const auto t0 = Clock::now();
    say("  building " + short_hash(s.commit) + (s.version.empty() ? "" : " (" + s.version + ")") +
        " ...");
    try {
      const runner::SourceBuildResult r = runner::build_from_source(b);
      s.build = r.build.name;
      s.build_dir = r.build.dir;
      s.reused = r.reused;
      s.build_s = r.seconds;
      say(r.reused ? "  reused build " + s.build
                   : "  built " + s.build + " in " + util::duration_text(r.seconds));
    } catch (const util::UserError& e) {
      s.verdict = StepVerdict::kSkip;
      s.reason = std::string("build failed: ") + e.what();
      s.build_s = std::chrono::duration<double>(Clock::now() - t0).count();
      return;
    }
    const auto t1 = Clock::now();
    s.drawing = draw_selection(o_, o_.platform, st_.result.selection, s.build_dir);
    s.draw_s = std::chrono::duration<double>(Clock::now() - t1).count();
  }

  void judge(BisectStep& s) const {
    if (s.build.empty()) return;  // a failed build: skipped, said by evaluate
    const auto [v, why] =
        judge_drawing(judged_, s.drawing, st_.result.good.drawing, st_.result.bad.drawing);
    s.verdict = v;
    s.reason = why;
  }

  // The good and the bad ref drawn; primitives both draw alike say nothing about the change.
  void draw_references() {
    for (auto [ref, commit, step, role] :
         {std::tuple{o_.good_ref, good_, &st_.result.good, "good ref"},
          std::tuple{o_.bad_ref, bad_, &st_.result.bad, "bad ref"}}) {
      if (step->commit == commit && step->drawing.error.empty() && !step->drawing.hashes.empty())
        continue;
      *step = BisectStep{};
      step->role = role;
      step->commit = commit;
      say(std::string(role) + " " + ref + " (" + short_hash(commit) + ")");
      evaluate(*step, commit);
      if (step->build.empty())
        throw util::UserError("bisect: the " + std::string(role) + " " + ref +
                              " cannot be built: " + step->reason);
      if (!step->drawing.error.empty())
        throw util::UserError("bisect: the build of the " + std::string(role) + " " + ref +
                              " cannot draw the selection with " + o_.platform + ": " +
                              step->drawing.error);
      step->verdict = step == &st_.result.good ? StepVerdict::kGood : StepVerdict::kBad;
      st_.save();
    }
    st_.result.dropped.clear();
    for (const BisectPrimitive& p : st_.result.selection) {
      const std::string l = p.label();
      if (st_.result.good.drawing.hashes.at(l) == st_.result.bad.drawing.hashes.at(l))
        st_.result.dropped.push_back(l);
      else
        judged_.push_back(p);
    }
    if (judged_.empty())
      throw util::UserError("bisect: the builds of " + o_.good_ref + " and " + o_.bad_ref +
                            " draw all " + std::to_string(st_.result.selection.size()) +
                            " selected primitives alike on " + o_.platform +
                            ": the change is not between these refs (or not in this platform)");
    if (!st_.result.dropped.empty())
      say(std::to_string(st_.result.dropped.size()) + " of " +
          std::to_string(st_.result.selection.size()) +
          " selected primitives are drawn alike by both refs and are left out");
  }

  // git bisect with the judged steps replayed, then new steps until git names the commit.
  GitBisectState bisect() {
    const GitResult branch = git(o_.source, {"symbolic-ref", "-q", "--short", "HEAD"});
    const std::string original = branch.ok ? branch.out : git(o_.source, {"rev-parse", "HEAD"}).out;
    std::error_code ec;
    if (fs::exists(git_dir_ + "/BISECT_START", ec)) git(o_.source, {"bisect", "reset"});
    std::vector<std::string> start = {"start", bad_, good_};
    if (!o_.paths.empty()) {
      start.push_back("--");
      start.insert(start.end(), o_.paths.begin(), o_.paths.end());
    }
    struct Reset {  // the tree back where it was, however this ends
      std::string dir, original;
      ~Reset() {
        git(dir, {"bisect", "reset"});
        git(dir, {"checkout", "-q", original});
      }
    } reset{o_.source, original};
    GitBisectState gs = parse_bisect_output(git_bisect(o_.source, start));
    for (const BisectStep& s : st_.result.steps) {
      if (gs.done) break;
      gs = parse_bisect_output(git_bisect(o_.source, {verdict_name(s.verdict), s.commit}));
    }
    double step_seconds = 0;
    int fresh_steps = 0;
    while (!gs.done) {
      BisectStep s;
      s.role = "step";
      s.commit = git_ok(o_.source, {"rev-parse", "HEAD"}, "git rev-parse");
      std::string eta;
      if (gs.steps_left >= 0) {
        eta = " (roughly " + std::to_string(gs.steps_left + 1) + " to go";
        if (fresh_steps > 0)
          eta += ", about " + util::duration_text(step_seconds / fresh_steps * (gs.steps_left + 1));
        eta += ")";
      }
      const auto t0 = Clock::now();
      say("step " + std::to_string(st_.result.steps.size() + 1) + eta + ": " + short_hash(s.commit) +
          " " + git(o_.source, {"log", "-1", "--format=%s", "HEAD"}).out);
      evaluate(s, "");
      judge(s);
      say("  " + std::string(verdict_name(s.verdict)) + ": " + s.reason);
      st_.result.steps.push_back(s);
      st_.save();
      step_seconds += std::chrono::duration<double>(Clock::now() - t0).count();
      ++fresh_steps;
      gs = parse_bisect_output(git_bisect(o_.source, {verdict_name(s.verdict), s.commit}));
    }
    return gs;
  }

  // The first bad commit and its parent, both drawn (by a step, or now).
  void confirm(const std::string& first_bad) {
    BisectResult& r = st_.result;
    r.found = true;
    r.first_bad = first_bad;
    BisectStep fb;
    fb.commit = first_bad;
    describe_commit(o_.source, fb);
    r.first_bad_subject = fb.subject;
    r.first_bad_date = fb.date;
    r.parent = git_ok(o_.source, {"rev-parse", first_bad + "^"}, "git rev-parse");
    for (auto [key, commit] : {std::pair{"first bad", r.first_bad}, std::pair{"parent", r.parent}}) {
      const BisectStep* known = nullptr;
      for (const BisectStep* s : {&r.good, &r.bad})
        if (s->commit == commit) known = s;
      for (const BisectStep& s : r.steps)
        if (s.commit == commit && !s.build.empty() && s.drawing.error.empty()) known = &s;
      if (known) {
        r.confirm[key] = *known;
        continue;
      }
      if (r.confirm.count(key) && r.confirm[key].commit == commit) continue;
      BisectStep c;
      c.role = std::string(key) == "parent" ? "parent of the first bad commit" : "first bad commit";
      c.commit = commit;
      say("confirming: drawing the " + c.role + " " + short_hash(commit));
      evaluate(c, commit);
      judge(c);
      say("  " + std::string(verdict_name(c.verdict)) + ": " + c.reason);
      r.confirm[key] = c;
      st_.save();
    }
    say("first bad commit: " + r.first_bad + " " + r.first_bad_subject + " (" + r.first_bad_date +
        ")");
  }

  BisectOptions o_;
  std::function<void(const std::string&)> progress_;
  State st_;
  std::string git_dir_, good_, bad_;
  std::vector<BisectPrimitive> judged_;  // the selection less what both refs draw alike
};

}  // namespace

BisectResult run_bisect(const BisectOptions& options,
                        const std::function<void(const std::string&)>& progress) {
  return Bisection(options, progress).run();
}

}  // namespace ra::triage
