// The developer report of a bisection (see the header).
#include "triage/bisect_report.h"

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>

#include "rundir/run_folder.h"
#include "triage/bisect.h"
#include "triage/bisect_rounds.h"
#include "triage/primitive_image.h"
#include "audit/reproducer.h"
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

// `show` of one primitive drawn with a step's build, in a child (one driver per process).
std::string picture(const BisectOptions& o, const BisectStep& s, const BisectPrimitive& p,
                    const std::string& out_png) {
  if (s.build_dir.empty()) return "";
  const std::string dir = o.out_dir + "/.show-" + short_hash(s.commit);
  std::error_code ec;
  fs::create_directories(dir, ec);
  util::write_file_atomic(rundir::run_folder::experiment(dir),
                          bisect_step_experiment(o.run_dir, s.build_dir));
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

namespace {

std::string group_letter(int g) { return g >= 0 && g < 26 ? std::string(1, char('A' + g)) : "-"; }

std::string cell(std::string text) {
  std::replace(text.begin(), text.end(), '|', '/');
  std::replace(text.begin(), text.end(), '\n', ' ');
  return text.size() > 160 ? text.substr(0, 157) + "..." : text;
}

// "3 lines of group D, 1 triangle of group B"
std::string composition(const std::vector<const BisectPrimitive*>& prims) {
  std::map<std::pair<int, int>, int> n;
  for (const BisectPrimitive* p : prims) ++n[{int(p->kind), p->view_group}];
  std::string out;
  for (const auto& [key, count] : n)
    out += std::string(out.empty() ? "" : ", ") + std::to_string(count) + " " +
           geometry::kind_name(geometry::Kind(key.first)) + (count == 1 ? "" : "s") +
           " of group " + group_letter(key.second);
  return out;
}

// The run's GL verdicts of the changed primitives, before and after ("within-spec -> violation:
// 3; exact -> snapped: 1").
std::string conformance_moves(const std::vector<const BisectPrimitive*>& prims) {
  std::map<std::pair<std::string, std::string>, int> n;
  for (const BisectPrimitive* p : prims) ++n[{p->run_good_conformance, p->run_bad_conformance}];
  std::string out;
  for (const auto& [key, count] : n)
    out += std::string(out.empty() ? "" : "; ") + (key.first.empty() ? "-" : key.first) + " -> " +
           (key.second.empty() ? "-" : key.second) + ": " + std::to_string(count);
  return out;
}

}  // namespace

namespace {

// One culprit's section: what it changed, the GL verdict, its files, the reproducer and pictures
// of its worst primitive, its primitives' pixels.
void write_culprit(std::ostringstream& md, int section, const Culprit& c, const BisectOptions& o,
                 const BisectResult& r, const std::string& driver,
                 const std::map<std::string, const BisectPrimitive*>& by_label,
                 const std::map<std::string, const BisectStep*>& by_commit) {
  std::vector<const BisectPrimitive*> prims;
  for (const std::string& l : c.primitives) prims.push_back(by_label.at(l));
  // Its worst primitive: the largest change of lit pixels.
  const BisectPrimitive* worst = prims.front();
  int64_t worst_change = -1;
  for (const BisectPrimitive* p : prims) {
    const auto [before, after] = c.pixels.at(p->label());
    if (std::llabs(after - before) > worst_change) worst = p, worst_change = std::llabs(after - before);
  }
  const std::string l = worst->label();
  const auto [before_px, after_px] = c.pixels.at(l);
  md << "\n<a id=\"commit-" << short_hash(c.commit) << "\"></a>\n## " << section << ". "
     << short_hash(c.commit) << " " << c.subject << "\n\n";
  md << "**What changed.** Since commit " << short_hash(c.commit) << " (" << c.date.substr(0, 10)
     << "), " << driver << " draws " << c.primitives.size() << " primitive"
     << (c.primitives.size() == 1 ? "" : "s") << " differently (" << composition(prims)
     << "); the largest change: " << l << " lit " << after_px << " pixels where "
     << short_hash(c.previous) << " lit " << before_px << ".";
  if (c.merge) md << " This is a merge commit: the change came with the branch it merged.";
  if (!o.paths.empty())
    md << " The commit before it is the previous one touching the paths given.";
  md << "\n\n";
  // The GL verdict: the run's record of the bad side, when this change gave the bad side's pixels.
  audit::Reproducer repro;
  std::string repro_error;
  const std::string c_name = std::string(geometry::kind_name(worst->kind)) + "-v" +
                             std::to_string(worst->view) + "-" + std::to_string(worst->index) + ".c";
  try {
    audit::ReproduceRequest q{o.run_dir, o.bad_platform.empty() ? o.platform : o.bad_platform,
                              geometry::kind_name(worst->kind), worst->view, worst->index};
    repro = audit::make_reproducer(q, c_name);
    util::write_file_atomic(o.out_dir + "/" + c_name, repro.source);
  } catch (const std::exception& e) {
    repro_error = e.what();
  }
  const BisectStep* after_step = by_commit.count(c.commit) ? by_commit.at(c.commit) : nullptr;
  const bool final_state = after_step && r.bad.drawing.hashes.count(l) &&
                           after_step->drawing.hashes.count(l) &&
                           after_step->drawing.hashes.at(l) == r.bad.drawing.hashes.at(l);
  if (!final_state) {
    md << "**GL verdict.** Not judged: this change leads to a state that a later commit changed "
          "again (the run judged only the bad ref's pixels).\n\n";
  } else if (!repro.violated_rules.empty()) {
    md << "**GL rule broken** (OpenGL 4.6 section 14.5.1 for lines, 14.6.1 polygons, 14.4 "
          "points; the run's verdict of the bad side):";
    const std::string& rules = repro.violated_rules;
    for (std::size_t at = 0; at <= rules.size();) {
      const std::size_t plus = std::min(rules.find('+', at), rules.size());
      const std::string rule = rules.substr(at, plus - at);
      md << " `" << rule << "`: " << rule_meaning(rule) << (plus < rules.size() ? ";" : ".");
      at = plus + 1;
    }
    md << "\n\n";
  } else if (repro_error.empty()) {
    md << "**GL verdict.** Allowed by GL: " << l << " keeps within the rules after the change "
       << "(the run's verdict of the bad side: "
       << (worst->run_bad_conformance.empty() ? "-" : worst->run_bad_conformance)
       << "); another rounding, not a violation.\n\n";
  }
  md << "```\ncommit " << c.commit << "\n" << files_changed(o.source, c.commit) << "```\n\n";
  const BisectStep* before_step =
      by_commit.count(c.previous) ? by_commit.at(c.previous) : nullptr;
  if (repro_error.empty()) {
    md << "**Reproducer** of " << l << (repro.view_text.empty() ? "" : " (" + repro.view_text + ")")
       << ": a standalone C program (EGL surfaceless, desktop GL), written as `" << c_name
       << "`; it prints the pixels it lit.\n\n```sh\n" << repro.build_line << "\n";
    const std::string exe = fs::path(c_name).stem().string();
    if (before_step && !before_step->build_dir.empty())
      md << audit::reproducer_environment(before_step->build_dir, driver) << " "
         << util::shell_quote("./" + exe)
         << "   # " << short_hash(c.previous) << ": " << before_px << " pixels\n";
    if (after_step && !after_step->build_dir.empty())
      md << audit::reproducer_environment(after_step->build_dir, driver) << " "
         << util::shell_quote("./" + exe)
         << "   # " << short_hash(c.commit) << ": " << after_px << " pixels\n";
    md << "```\n\n<details><summary>" << c_name << "</summary>\n\n```c\n" << repro.source
       << "```\n\n</details>\n\n";
  } else {
    md << "No C reproducer: " << repro_error << "\n\n";
  }
  if (o.pictures && before_step && after_step) {
    md << "**Pictures** of " << l << ": white unlit, grey lit by both, orange lit by the driver "
          "only, blue lit by the reference only, black a pixel GL forbids; the red line is the "
          "ideal projection.\n\n";
    fs::create_directories(o.out_dir + "/pictures");
    for (const auto& [side, s] : {std::pair{"before", before_step}, std::pair{"after", after_step}}) {
      const std::string png = o.out_dir + "/pictures/" + short_hash(c.commit) + "-" + side + "." +
                              geometry::kind_name(worst->kind) + ".v" +
                              std::to_string(worst->view) + "." + std::to_string(worst->index) +
                              ".png";
      const std::string got = picture(o, *s, *worst, png);
      md << "- " << side << " (" << short_hash(s->commit) << "): "
         << (got.empty() ? "no picture (see the command's output)"
                         : "\n\n  ![" + std::string(side) + "](pictures/" +
                               fs::path(png).filename().string() + ")")
         << "\n";
    }
    md << "\n";
  }
  md << stats::markdown_header({"primitive", "group", "pixels before", "pixels after",
                                "run verdicts, before -> after"},
                               1);
  for (const BisectPrimitive* p : prims) {
    const auto [b, a] = c.pixels.at(p->label());
    md << "| " << p->label() << " | " << group_letter(p->view_group) << " | " << b << " | " << a
       << " | " << (p->run_good_conformance.empty() ? "-" : p->run_good_conformance) << " -> "
       << (p->run_bad_conformance.empty() ? "-" : p->run_bad_conformance) << " |\n";
  }
  }

// "3.025x the time (95%: 2.597-3.525; the A/A control 0.996x)"
std::string time_words(const audit::SpeedComparison& c) {
  if (!std::isfinite(c.ratio)) return "no ratio (" + (c.reason.empty() ? "too few rounds" : c.reason) + ")";
  char text[160];
  std::snprintf(text, sizeof text, "%.3fx the time (95%%: %.3f-%.3f; the A/A control %.3fx)",
                c.ratio, c.low, c.high, c.control_ratio);
  return text;
}

// The drawing time at the ends, each speed culprit, and what stays unattributed.
void write_speed(std::ostringstream& md, int section, const BisectOptions& o, const BisectResult& r,
                 const std::string& driver) {
  md << "\n## Drawing time\n\nThe first " << o.speed.per_view
     << " primitives of each kind and view of every group, drawn alone by the good ref, the bad "
        "ref and the good ref again (an A/A control), "
     << o.speed.repeats
     << " rounds of fresh processes taking turns; the ratio is the bad ref's time over the good "
        "ref's, with its 95% interval over the rounds. A group moved when its whole interval lies "
        "beyond "
     << 100 * o.speed.threshold
     << "% and beyond the control's ratio (the band).\n\n"
     << stats::markdown_header({"group", "good ref median (us)", "bad ref median (us)",
                                "bad / good [95%]", "control [95%]", "band", "verdict"},
                               1);
  for (const SpeedAtEnds& e : r.speed_ends) {
    const audit::SpeedComparison& c = e.comparison;
    char medians[96];
    std::snprintf(medians, sizeof medians, "%.1f | %.1f", c.baseline_median_us, c.current_median_us);
    char band[32];
    std::snprintf(band, sizeof band, "%.3f", c.band);
    md << "| " << e.group.text() << " | " << medians << " | "
       << audit::speed_ratio_text(c.ratio, c.low, c.high) << " | "
       << audit::speed_ratio_text(c.control_ratio, c.control_low, c.control_high) << " | " << band
       << " | " << audit::speed_verdict_name(c.verdict)
       << (c.verdict == audit::SpeedVerdict::kUnknown
               ? (!c.reason.empty() ? ", " + c.reason
                  : c.repeats_to_settle > 0
                      ? ", not attributed (about " + std::to_string(c.repeats_to_settle) +
                            " repeats would settle it)"
                      : ", not attributed (at the band's edge)")
               : std::string())
       << " |\n";
  }
  for (const SpeedCulprit& c : r.speed_culprits) {
    md << "\n<a id=\"time-" << short_hash(c.commit) << "\"></a>\n## " << ++section
       << ". Drawing time: " << short_hash(c.commit) << " " << c.subject << "\n\n**What changed.** "
       << "At commit " << short_hash(c.commit) << " (" << c.date.substr(0, 10) << "), " << driver
       << " draws";
    for (std::size_t i = 0; i < c.moves.size(); ++i) {
      const SpeedCulprit::Move& m = c.moves[i];
      md << (i == 0 ? " " : i + 1 == c.moves.size() ? " and " : ", ") << "the "
         << m.group.text() << " " << audit::speed_verdict_name(m.direction);
    }
    if (!c.beside_note.empty())
      md << " than " << short_hash(c.previous)
         << ", the commit before it among those touching the paths given; " << c.beside_note;
    else if (c.beside != c.previous)
      md << " than " << short_hash(c.beside) << ", its git parent (the commit before it among "
         << "those touching the paths given is " << short_hash(c.previous) << ")";
    else
      md << " than " << short_hash(c.previous) << ", the commit before it";
    md << ". Confirmed by drawing the two beside each other (the commit before drawn twice, the "
          "control), the commit's time over the one before:\n\n"
       << stats::markdown_header(
              {"group", "direction", "time over the commit before", "verdict of the confirmation"},
              4);
    for (const SpeedCulprit::Move& m : c.moves)
      md << "| " << m.group.text() << " | " << audit::speed_verdict_name(m.direction) << " | "
         << (m.error.empty() ? time_words(m.confirmation) : "not timed: " + cell(m.error)) << " | "
         << (m.error.empty() ? audit::speed_verdict_name(m.confirmation.verdict) : "-") << " |\n";
    md << "\n**How it was found.** Each step's time of the group was placed between the ends' "
          "(0% the good ref's time, 100% the bad ref's, on a log scale): \"as bad\" when the 95% "
          "interval lies above the middle, \"as good\" below it.\n\n"
       << stats::markdown_header({"step", "commit", "group", "step / good ref [95%]",
                                  "of the way [95%]", "rounds", "place"},
                                 3);
    const auto row = [&](const std::string& step, const std::string& commit, const StepTime& t) {
      bool mine = false;
      for (const SpeedCulprit::Move& m : c.moves) mine = mine || m.group == t.group;
      if (!mine) return;
      char share[96] = "-";
      if (std::isfinite(t.share))
        std::snprintf(share, sizeof share, "%.0f%% [%.0f%%, %.0f%%]", 100 * t.share,
                      100 * t.share_low, 100 * t.share_high);
      md << "| " << step << " | " << short_hash(commit) << " | " << t.group.text() << " | "
         << audit::speed_ratio_text(t.ratio, t.low, t.high) << " | " << share << " | "
         << t.repeats << " | " << time_place_name(t.place)
         << (t.note.empty() ? "" : " (" + cell(t.note) + ")") << " |\n";
    };
    int n = 0;
    for (const BisectStep& s : r.steps) {
      ++n;
      for (const StepTime& t : s.speed) row(std::to_string(n), s.commit, t);
    }
    for (const StepTime& t : c.parent_places) row("git parent", c.beside, t);
    const std::string files = files_changed(o.source, c.commit);
    if (!files.empty()) md << "\n**The commit.**\n\n```\n" << files << "```\n";
  }
  if (!r.speed_unattributed.empty()) {
    md << "\n## Drawing time not attributed\n\n"
       << stats::markdown_header({"group", "placed before", "placed after", "why", "candidates"}, 5);
    for (const SpeedUnattributed& u : r.speed_unattributed) {
      std::string cands;
      for (const std::string& c : u.candidates) cands += (cands.empty() ? "" : " ") + short_hash(c);
      md << "| " << u.group.text() << " | " << short_hash(u.from) << " | " << short_hash(u.to)
         << " | " << cell(u.why) << " | " << (cands.empty() ? "-" : cands) << " |\n";
    }
    for (const SpeedUnattributed& u : r.speed_unattributed)
      if (!u.next_command.empty())
        md << "\nThe bisection that names the " << u.group.text() << " move:\n\n```sh\n"
           << u.next_command << "\n```\n";
  }
}

}  // namespace

void write_bisect_report(const BisectOptions& o, const BisectResult& r,
                         const std::vector<BisectPrimitive>& judged,
                         const std::function<void(const std::string&)>& say) {
  const rundir::PlatformSpec spec = *rundir::find_platform(o.platform + "@" + kStepBuild);
  const std::string driver = spec.mesa_driver.empty() ? o.platform : spec.mesa_driver;
  std::map<std::string, const BisectPrimitive*> by_label;
  for (const BisectPrimitive& p : judged) by_label[p.label()] = &p;
  std::map<std::string, const BisectStep*> by_commit = {{r.good.commit, &r.good},
                                                         {r.bad.commit, &r.bad}};
  for (const BisectStep& s : r.steps)
    if (s.error.empty()) by_commit[s.commit] = &s;

  std::ostringstream md;
  std::size_t moved = 0;
  for (const SpeedAtEnds& e : r.speed_ends) moved += e.moved() ? 1 : 0;
  const std::string time_title = "drawing time of " + std::to_string(moved) +
                                 (moved == 1 ? " group" : " groups") + " moved, " +
                                 std::to_string(r.speed_culprits.size()) + " commit" +
                                 (r.speed_culprits.size() == 1 ? "" : "s");
  const auto version = [](const BisectStep& s) {
    return s.version.empty() ? std::string() : " (" + s.version + ")";
  };
  std::string range = "Between " + short_hash(r.good.commit) + version(r.good) + " and " +
                      short_hash(r.bad.commit) + version(r.bad) + ", " +
                      std::to_string(r.commits_in_range) + " commits";
  if (!o.paths.empty()) {
    range += " touching";
    for (const std::string& p : o.paths) range += " `" + p + "`";
  }
  if (judged.empty()) {  // drawing time only (--speed)
    md << "# " << driver << ": " << time_title << "\n\n"
       << range << ", " << driver << " (through " << o.platform
       << ") draws every selected primitive alike (" << r.selection_rule
       << "); its drawing time is below.\n";
  } else {
    md << "# " << driver << ": " << judged.size() << " changed primitives, "
       << r.culprits.size() << " culprit commit" << (r.culprits.size() == 1 ? "" : "s");
    if (o.speed.enabled) md << "; " << time_title;
    md << "\n\n" << range << ", " << driver << " (through " << o.platform << ") draws " << judged.size()
       << " of the selected primitives differently. Selection: " << r.selection_rule << ".";
    if (!r.dropped.empty())
      md << " " << r.dropped.size() << " selected primitives drew alike on both refs' builds and "
         << "were left out.";
    md << "\n\n| commit | subject | date | primitives | which | GL verdicts in the run, before -> "
          "after |\n| --- | --- | --- | ---: | --- | --- |\n";
    for (const Culprit& c : r.culprits) {
      std::vector<const BisectPrimitive*> prims;
      for (const std::string& l : c.primitives) prims.push_back(by_label.at(l));
      md << "| [" << short_hash(c.commit) << "](#commit-" << short_hash(c.commit) << ") | "
         << cell(c.subject) << " | " << c.date.substr(0, 10) << " | " << c.primitives.size()
         << " | " << composition(prims) << " | " << conformance_moves(prims) << " |\n";
    }
    if (!r.unattributed.empty())
      md << "| (unattributed) | only failed builds between two drawn commits | | "
         << r.unattributed.size() << " | | |\n";
    std::size_t attributed = 0;
    for (const Culprit& c : r.culprits) attributed += c.primitives.size();
    md << "\nChanges attributed: " << attributed << "; unattributed: " << r.unattributed.size()
       << " (a primitive changed twice counts twice).\n";
  }
  int section = 0;
  for (const Culprit& c : r.culprits) write_culprit(md, ++section, c, o, r, driver, by_label, by_commit);
  if (o.speed.enabled) write_speed(md, section, o, r, driver);
  if (!r.unattributed.empty()) {
    md << "\n## Unattributed\n\nOnly commits that failed to build lie between two drawn commits: "
          "each of these changes was made by one of its candidates.\n\n"
       << stats::markdown_header({"primitive", "drawn before", "drawn after", "candidates"}, 1);
    for (const Unattributed& u : r.unattributed) {
      std::string cands;
      for (const std::string& c : u.candidates) cands += (cands.empty() ? "" : " ") + short_hash(c);
      md << "| " << u.label << " | " << short_hash(u.from) << " | " << short_hash(u.to) << " | "
         << cands << " |\n";
    }
  }
  md << "\n## The bisection\n\n" << r.steps.size() << " steps over " << r.commits_in_range
     << " commits; builds took " << util::duration_text(r.total_build_s) << " in all.\n\n"
     << "| # | commit | subject | drew | build |\n| ---: | --- | --- | --- | ---: |\n";
  int n = 0;
  for (const BisectStep& s : r.steps)
    md << "| " << ++n << " | " << short_hash(s.commit) << " | " << cell(s.subject) << " | "
       << cell(s.error.empty() ? s.summary : s.error) << " | "
       << (s.reused ? "reused" : util::duration_text(s.build_s)) << " |\n";
  if (!r.rounds.empty()) {
    md << "\n" << rounds_summary(r) << ":\n\n"
       << "| round | builds | where | failed | cancelled | unresolved before | building | round |\n"
       << "| ---: | --- | --- | ---: | ---: | ---: | ---: | ---: |\n";
    for (const BisectRound& round : r.rounds) {
      std::string commits;
      for (const std::string& c : round.commits) commits += (commits.empty() ? "" : " ") + short_hash(c);
      md << "| " << round.round << " | " << commits << " | " << round.where << " | "
         << round.failed.size() << " | " << round.cancelled.size() << " | " << round.unresolved
         << " | " << util::duration_text(round.build_wall_s) << " | "
         << (round.finished ? util::duration_text(round.seconds) : std::string("interrupted"))
         << " |\n";
    }
  }
  md << "\n## Repeat it\n\n```sh\n" << o.command_line << "\n```\n";
  util::write_file_atomic(r.report_path, md.str());
  say("report: " + r.report_path);
}

}  // namespace ra::triage
