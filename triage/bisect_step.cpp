// One step of a bisection: a commit built and drawn (see the header).
#include "triage/bisect_step.h"

#include <chrono>

#include "audit/flake_check.h"
#include "rundir/run_experiment.h"
#include "builds/git_command.h"
#include "triage/bisect.h"
#include "util/duration_text.h"
#include "util/errors.h"
#include "util/interrupt.h"

using Clock = std::chrono::steady_clock;

namespace ra::triage {

using builds::git;
using builds::GitResult;

std::string short_hash(const std::string& c) { return c.substr(0, 12); }

void describe_commit(const std::string& dir, BisectStep& s) {
  const std::string info = git(dir, {"log", "-1", "--format=%cI%n%s", s.commit}).out;
  s.date = info.substr(0, info.find('\n'));
  s.subject = info.find('\n') == std::string::npos ? "" : info.substr(info.find('\n') + 1);
  const GitResult v = git(dir, {"show", s.commit + ":VERSION"});
  s.version = v.ok ? v.out : "";
}

std::string bisect_step_experiment(const std::string& run_dir, const std::string& build_dir) {
  std::string text = rundir::load_run_experiment(run_dir).text;  // as the records were drawn
  if (!text.empty() && text.back() != '\n') text += '\n';
  nlohmann::json dir = build_dir;  // a JSON string is a valid TOML basic string
  return text + "\n[builds." + kStepBuild +
         "]   # added by renderaudit bisect\ndir = " + dir.dump() + "\n";
}

Drawing draw_selection(const BisectOptions& o, const std::vector<BisectPrimitive>& selection,
                       const std::string& build_dir) {
  std::vector<audit::RerenderRequest> requests;
  const std::string qualified = o.platform + "@" + kStepBuild;
  for (const BisectPrimitive& p : selection)
    requests.push_back({qualified, p.kind, p.view, p.index});
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

void build_and_draw_step(const BisectOptions& o, const std::vector<BisectPrimitive>& primitives,
                         BisectStep& s, const std::function<void(const std::string&)>& say) {
  describe_commit(o.source, s);
  builds::SourceBuildOptions b = o.build;
  b.source = o.source;
  b.ref = s.commit;
  b.probe = false;  // the drawing is the probe
  b.source_locked = true;
  b.restore_ref = false;  // restored once, at the end
  const auto t0 = Clock::now();
  std::shared_ptr<builds::BuildInUse> in_use;  // the build kept from `builds remove` while drawn
  say("  building " + short_hash(s.commit) + (s.version.empty() ? "" : " (" + s.version + ")") +
      " ...");
  try {
    // Of the build's own lines, only the compile's progress: a distant commit compiles for minutes.
    const builds::SourceBuildResult r = builds::build_from_source(b, [&](const std::string& line) {
      if (line.rfind("compile (ninja)", 0) == 0) say("    " + line);
    });
    in_use = r.in_use;
    s.build = r.build.name;
    s.build_dir = r.build.dir;
    s.reused = r.reused;
    s.build_s = r.seconds;
    say(r.reused ? "  reused build " + s.build
                 : "  built " + s.build + " in " + util::duration_text(r.seconds));
  } catch (const util::UserError& e) {
    util::throw_if_interrupted();
    s.error = std::string("build failed: ") + e.what();
    s.build_s = std::chrono::duration<double>(Clock::now() - t0).count();
    return;
  }
  util::throw_if_interrupted();
  draw_built_step(o, primitives, s);
}

void draw_built_step(const BisectOptions& o, const std::vector<BisectPrimitive>& primitives,
                     BisectStep& s) {
  if (primitives.empty()) return;  // drawing time only (--speed): timed by the caller
  const auto t1 = Clock::now();
  s.drawing = draw_selection(o, primitives, s.build_dir);
  s.draw_s = std::chrono::duration<double>(Clock::now() - t1).count();
  util::throw_if_interrupted();
  if (!s.drawing.error.empty()) s.error = "drawing failed: " + s.drawing.error;
}

}  // namespace ra::triage
