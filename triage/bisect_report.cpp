// The developer report of a bisection (see the header).
#include "triage/bisect_report.h"

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>

#include "triage/primitive_image.h"
#include "audit/reproducer.h"
#include "rundir/driver_build.h"
#include "rundir/platform_spec.h"
#include "stats/table_writer.h"
#include "util/atomic_file.h"
#include "util/child_process.h"
#include "util/duration_text.h"
#include "util/errors.h"
#include "util/shell_quote.h"

namespace fs = std::filesystem;

namespace ra::triage {
namespace {

std::string short_hash(const std::string& c) { return c.substr(0, 12); }

std::string pixels_of(const BisectStep& s, const std::string& label) {
  const auto it = s.drawing.pixels.find(label);
  return it == s.drawing.pixels.end() ? "-" : std::to_string(it->second);
}

// `show` of one primitive drawn with a step's build, in a child (one driver per process).
std::string picture(const BisectOptions& o, const BisectStep& s, const BisectPrimitive& p,
                    const std::string& out_png) {
  if (s.build_dir.empty()) return "";
  const std::string dir = o.out_dir + "/.show-" + short_hash(s.commit);
  std::error_code ec;
  fs::create_directories(dir, ec);
  util::write_file_atomic(dir + "/experiment.toml", bisect_step_experiment(o.run_dir, s.build_dir));
  const pid_t pid = util::fork_child([&] {
    try {
      ShowRequest q;
      q.run_dir = dir;
      q.platform = o.platform + "@" + kStepBuild;
      q.kind = geometry::kind_name(p.kind);
      q.view = p.view;
      q.index = p.index;
      q.out_path = out_png;
      show_primitive(q);
      return 0;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "bisect: no picture of %s: %s\n", p.label().c_str(), e.what());
      return 1;
    }
  });
  const int status = util::wait_child(pid);
  fs::remove_all(dir, ec);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0 && fs::exists(out_png) ? out_png : "";
}

std::string files_changed(const std::string& source, const std::string& commit) {
  util::ChildSpec spec;
  spec.argv = {"git", "-C", source, "show", "--stat=100", "--format=%an <%ae>%n%n%B", commit};
  spec.stdin_null = true;
  spec.capture_output = true;
  const util::ProgramResult r = util::run_program(spec);
  return r.exited_ok() ? r.output : "";
}

}  // namespace

std::string rule_meaning(const std::string& rule) {
  static const std::map<std::string, std::string> m = {
      {"line-missing", "a line drawn as nothing where GL requires fragments inside the window"},
      {"line-window-count",
       "a window-cut line with fewer or more fragments inside the window than diamond-exit allows"},
      {"line-count", "a line whose fragment count differs from diamond-exit's by more than one"},
      {"line-deviation", "a line fragment more than one pixel from every diamond-exit fragment"},
      {"line-column", "two fragments in one column of an x-major line (or one row of a y-major)"},
      {"line-rectangle", "a fragment outside the rectangle a strict Vulkan line covers"},
      {"polygon-edge", "a polygon pixel lit or left dark farther from an edge than GL allows"},
      {"polygon-missing", "a polygon drawn as nothing though a pixel lies inside every edge"},
      {"point-pixel", "a point's fragment farther from its position than GL allows"},
      {"point-count", "a size-1 point drawn as more than one fragment"},
      {"point-missing", "a point drawn as nothing well inside the window"},
  };
  const auto it = m.find(rule);
  return it == m.end() ? rule : it->second;
}

void write_bisect_report(const BisectOptions& o, const BisectResult& r,
                         const std::vector<BisectPrimitive>& judged,
                         const std::function<void(const std::string&)>& say) {
  const BisectPrimitive& worst = judged.front();
  const rundir::PlatformSpec spec = *rundir::find_platform(o.platform + "@" + kStepBuild);
  const std::string driver = spec.mesa_driver.empty() ? o.platform : spec.mesa_driver;
  const BisectStep* first_bad = r.confirm.count("first bad") ? &r.confirm.at("first bad") : nullptr;
  const BisectStep* parent = r.confirm.count("parent") ? &r.confirm.at("parent") : nullptr;
  const BisectStep& good_side = parent ? *parent : r.good;
  const BisectStep& bad_side = first_bad ? *first_bad : r.bad;
  const std::string l = worst.label();

  // The C reproducer, from the run's record on the bad platform (or the drawing platform).
  audit::Reproducer repro;
  std::string repro_error;
  const std::string c_name = std::string(geometry::kind_name(worst.kind)) + "-v" +
                             std::to_string(worst.view) + "-" + std::to_string(worst.index) + ".c";
  try {
    audit::ReproduceRequest q{o.run_dir, o.bad_platform.empty() ? o.platform : o.bad_platform,
                       geometry::kind_name(worst.kind), worst.view, worst.index};
    repro = audit::make_reproducer(q, c_name);
    util::write_file_atomic(o.out_dir + "/" + c_name, repro.source);
  } catch (const std::exception& e) {
    repro_error = e.what();
  }

  std::ostringstream md;
  const std::string change = r.found ? short_hash(r.first_bad) : "(not found)";
  md << "# " << driver << ": " << l << " drawn with " << pixels_of(bad_side, l)
     << " pixels instead of " << pixels_of(good_side, l) << " since " << change << "\n\n";
  md << "**What is wrong.** Since " << (r.found ? "commit " + short_hash(r.first_bad) + " (\"" +
                                                      r.first_bad_subject + "\")"
                                                : "a commit between the refs below")
     << ", " << driver << " (through " << o.platform << ") draws " << l;
  if (!repro.view_text.empty()) md << " (" << repro.view_text << ")";
  md << " with " << pixels_of(bad_side, l) << " lit pixels where its parent lit "
     << pixels_of(good_side, l);
  if (repro_error.empty()) md << " and the exact reference rasterizer lights " << repro.reference_pixels;
  md << "; " << judged.size() << " of the " << r.selection.size()
     << " selected primitives change the same way.\n\n";
  if (!repro.violated_rules.empty()) {
    md << "**GL rule broken** (OpenGL 4.6 section 14.5.1 for lines, 14.6.1 polygons, 14.4 points; "
          "renderaudit's conformance verdict of the run's record):";
    std::string rules = repro.violated_rules;
    for (std::size_t at = 0; at <= rules.size();) {
      const std::size_t plus = std::min(rules.find('+', at), rules.size());
      const std::string rule = rules.substr(at, plus - at);
      md << " `" << rule << "`: " << rule_meaning(rule) << (plus < rules.size() ? ";" : ".");
      at = plus + 1;
    }
    md << "\n\n";
  }
  md << "## Versions\n\n| side | commit | VERSION | date | " << l << " |\n| --- | --- | --- | --- | ---: |\n";
  const auto row = [&](const std::string& side, const BisectStep& s) {
    md << "| " << side << " | " << short_hash(s.commit) << " " << s.subject << " | " << s.version
       << " | " << s.date.substr(0, 10) << " | " << pixels_of(s, l) << " |\n";
  };
  row("good ref (unaffected)", r.good);
  if (parent) row("parent of the first bad commit (unaffected)", *parent);
  if (first_bad) row("**first bad commit**", *first_bad);
  row("bad ref (affected)", r.bad);
  if (!o.good_platform.empty())
    md << "\nThe run compared `" << o.good_platform << "` with `" << o.bad_platform
       << "` (its `drivers/*.json` name their GL_VERSION).\n";
  if (r.found) {
    md << "\n## The first bad commit\n\n```\ncommit " << r.first_bad << "\n"
       << files_changed(o.source, r.first_bad) << "```\n";
  } else {
    md << "\n## No single commit\n\nSkipped commits (that did not build or drew neither "
          "side's pixels) leave these candidates:\n\n";
    for (const std::string& c : r.candidates) md << "- " << c << "\n";
  }
  md << "\n## Reproducer\n\n";
  if (repro_error.empty()) {
    md << "A standalone C program (EGL surfaceless, desktop GL; the primitive's coordinates as hex "
          "floats), also written as `" << c_name << "`:\n\n```sh\n" << repro.build_line << "\n";
    const std::string exe = fs::path(c_name).stem().string();
    if (parent && !parent->build_dir.empty())
      md << audit::reproducer_environment(parent->build_dir, driver) << " " << util::shell_quote("./" + exe) << "   # parent: pixels lit "
         << pixels_of(*parent, l) << "\n";
    if (first_bad && !first_bad->build_dir.empty())
      md << audit::reproducer_environment(first_bad->build_dir, driver) << " " << util::shell_quote("./" + exe) << "   # first bad: pixels lit "
         << pixels_of(*first_bad, l) << "\n";
    md << "```\n\n```c\n" << repro.source << "```\n";
  } else {
    md << "No C reproducer: " << repro_error << "\n";
  }
  if (o.pictures) {
    md << "\n## Pictures\n\n" << l << "; white unlit, grey lit by both, orange lit by the driver "
          "only, blue lit by the reference only, black a pixel GL forbids; the red line is the "
          "ideal projection.\n\n";
    fs::create_directories(o.out_dir + "/pictures");
    for (const auto& [side, s] : {std::pair{"parent", &good_side}, std::pair{"first-bad", &bad_side}}) {
      const std::string png = o.out_dir + "/pictures/" + side + "." +
                              geometry::kind_name(worst.kind) + ".v" + std::to_string(worst.view) +
                              "." + std::to_string(worst.index) + ".png";
      const std::string got = picture(o, *s, worst, png);
      if (got.empty())
        md << "- " << side << " (" << short_hash(s->commit) << "): no picture (see the command's "
           << "output)\n";
      else
        md << "- " << side << " (" << short_hash(s->commit) << "):\n\n  ![" << side << "](pictures/"
           << fs::path(png).filename().string() << ")\n";
    }
  }
  md << "\n## Every selected primitive\n\n"
     << stats::markdown_header({"primitive", "run: " + o.good_platform, "run: " + o.bad_platform,
                                "good ref", "parent", "first bad", "bad ref"},
                               1);
  for (const BisectPrimitive& p : r.selection) {
    const std::string pl = p.label();
    const bool dropped = std::find(r.dropped.begin(), r.dropped.end(), pl) != r.dropped.end();
    md << "| " << pl << (dropped ? " (drawn alike by both refs: left out)" : "") << " | "
       << (p.run_good_pixels >= 0 ? std::to_string(p.run_good_pixels) : "-") << " | "
       << (p.run_bad_pixels >= 0 ? std::to_string(p.run_bad_pixels) : "-") << " | "
       << pixels_of(r.good, pl) << " | " << (parent ? pixels_of(*parent, pl) : "-") << " | "
       << (first_bad ? pixels_of(*first_bad, pl) : "-") << " | " << pixels_of(r.bad, pl) << " |\n";
  }
  md << "\n## The bisection\n\n" << r.steps.size() << " steps";
  if (!o.paths.empty()) {
    md << " over the commits touching";
    for (const std::string& p : o.paths) md << " `" << p << "`";
  }
  md << "; builds took " << util::duration_text(r.total_build_s) << " in all.\n\n"
     << "| # | commit | subject | verdict | why | build |\n| ---: | --- | --- | --- | --- | ---: |\n";
  int n = 0;
  for (const BisectStep& s : r.steps) {
    std::string why = s.reason;
    std::replace(why.begin(), why.end(), '|', '/');
    std::replace(why.begin(), why.end(), '\n', ' ');
    if (why.size() > 160) why = why.substr(0, 157) + "...";
    md << "| " << ++n << " | " << short_hash(s.commit) << " | " << s.subject << " | "
       << verdict_name(s.verdict) << " | " << why << " | "
       << (s.reused ? "reused" : util::duration_text(s.build_s)) << " |\n";
  }
  md << "\n## Repeat it\n\n```sh\n" << o.command_line << "\n```\n";
  util::write_file_atomic(r.report_path, md.str());
  say("report: " + r.report_path);
}

}  // namespace ra::triage
