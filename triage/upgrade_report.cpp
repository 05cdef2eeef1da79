// The driver upgrade report in Markdown (see the header).
#include "triage/upgrade_report.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include "analysis/run_records.h"
#include "audit/reproducer.h"
#include "report/upgrade_sentences.h"
#include "rundir/run_folder.h"
#include "triage/primitive_image.h"
#include "util/atomic_file.h"
#include "util/gl_child_process.h"
#include "util/shell_quote.h"

namespace fs = std::filesystem;

namespace ra::triage {
namespace {

using audit::ChangedPrimitive;

// A file under the run folder as the Markdown names it: relative to the run.
std::string in_run(const std::string& path, const std::string& run_dir) {
  return fs::path(path).lexically_relative(run_dir).string();
}

// Draws one side of a picture pair, `show --against` the other, in a child of its own: a process
// keeps the first Mesa it loads, and the two sides are two Mesas. A picture that cannot be drawn
// is left out; the report still names it.
void draw_picture(const ShowRequest& q, const std::string& scratch) {
  try {
    util::run_in_child(scratch, "upgrade-picture", [&] {
      show_primitive(q);
      return nlohmann::json::object();
    });
  } catch (const std::exception& e) {
    std::fprintf(stderr, "renderaudit: upgrade report: no picture %s (%s)\n", q.out_path.c_str(),
                 e.what());
  }
}

// The C program that draws the primitive on `platform`, written beside the pictures; its build
// line, or "" when none could be made.
std::string reproducer_build_line(const std::string& run_dir, const std::string& platform,
                                  const ChangedPrimitive& c, const std::string& path) {
  try {
    const audit::Reproducer r = audit::make_reproducer(
        {run_dir, platform, geometry::kind_name(c.kind), c.view, c.index}, path);
    util::write_file_atomic(path, r.source);
    return r.build_line;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "renderaudit: upgrade report: no C program %s (%s)\n", path.c_str(),
                 e.what());
    return "";
  }
}

// The primitive drawn by both sides, side by side, with the commands that draw it again.
std::string picture_pair(const UpgradeFindings& u, const ShownPrimitive& s) {
  const std::string& run = u.summary.run_dir;
  const UpgradeSide& side = u.sides[s.side];
  const ChangedPrimitive& c = s.primitive;
  const std::string kind = geometry::kind_name(c.kind);
  const std::string pictures = rundir::run_folder::upgrade_pictures(run);
  fs::create_directories(pictures);
  const std::string name = "." + kind + ".v" + std::to_string(c.view) + "." +
                           std::to_string(c.index);
  std::string cells;
  for (const auto& [platform, other, state, label] :
       {std::tuple(side.platform, side.build_platform, c.before, "installed"),
        std::tuple(side.build_platform, side.platform, c.after, "upgraded")}) {
    ShowRequest q{run, platform, kind, c.view, c.index, pictures + "/" + platform + name + ".png",
                  0, other};
    draw_picture(q, pictures);
    const std::string verdict = state.conformance == metrics::Conformance::kNotCompared
                                    ? "not judged"
                                    : metrics::conformance_name(state.conformance);
    cells += std::string(cells.empty() ? "" : " ") + "![" + label + ", " + platform + ": " +
             std::to_string(state.pixels) + " pixels lit, " +
             metrics::visibility_name(state.visibility) + ", " + verdict + "](" +
             in_run(q.out_path, run) + ")";
  }
  report::UpgradeViewGroup group;
  for (const report::UpgradeViewGroup& g : u.summary.groups)
    if (g.label == analysis::view_group_label(c.view_group)) group = g;
  // a command to paste: every word one shell word, whatever the run folder is called
  const std::string show =
      "renderaudit show " + util::shell_command({run, "--platform", side.build_platform, "--kind",
                                                 kind, "--view", std::to_string(c.view),
                                                 "--index", std::to_string(c.index)});
  const std::string window = std::to_string(group.window);
  std::string out =
      cells + "\n\n" + kind + " " + std::to_string(c.index) + " of view " +
      std::to_string(c.view) + " (FOV " + std::to_string(group.fov_deg) + ", " + window + " x " +
      window +
      "). Grey: lit by the driver and the exact reference rasterizer; orange: by the driver only; "
      "blue: by the reference only; black: lit where GL forbids it; hatched green: left dark "
      "where GL requires it (both ringed in magenta); red: the ideal primitive. The framed pixels "
      "are enlarged under each picture, those the two drivers draw otherwise dotted in magenta. `" +
      show + "` draws it again.";
  const std::string program = pictures + "/" + side.build_platform + name + ".c";
  const std::string build = reproducer_build_line(run, side.build_platform, c, program);
  if (!build.empty())
    out += "\nA C program that draws it: `" + in_run(program, run) + "` (" + build + ").";
  return out + "\n";
}

// "25.0.7, 25.2.4": the Mesa versions of one side of every pair, sorted, each once.
std::string mesa_versions(const report::UpgradeSummary& s, bool build) {
  std::set<std::string> versions;
  for (const report::UpgradePair& p : s.pairs)
    if (std::string v = report::mesa_version(build ? p.build_version : p.installed_version);
        !v.empty())
      versions.insert(v);
  std::string out;
  for (const std::string& v : versions) out += (out.empty() ? "" : ", ") + v;
  return out;
}

// Counts of (kind, group, before, after), the most frequent first.
using Transitions = std::map<std::tuple<std::string, std::string, std::string, std::string>,
                             std::int64_t>;
void transition_rows(std::ostringstream& md, const Transitions& t) {
  std::vector<std::pair<Transitions::key_type, std::int64_t>> rows(t.begin(), t.end());
  std::stable_sort(rows.begin(), rows.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  for (const auto& [key, n] : rows)
    md << "| " << std::get<0>(key) << " | " << std::get<1>(key) << " | " << std::get<2>(key)
       << " | " << std::get<3>(key) << " | " << n << " |\n";
}

// One pair's section: its counts per kind and view group and how its primitives changed.
void pair_section(std::ostringstream& md, const report::UpgradePair& pair, const UpgradeSide& s) {
  md << "\n# " << pair.platform << " -> " << pair.build_platform << "\n\n"
     << "### Changed primitives per kind and view group\n\n"
     << "| kind | group | compared | changed | share | not drawn | new violations | as GL "
        "allows |\n| --- | :---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  for (const report::UpgradeStratum& t : pair.strata) {
    char share[32];
    std::snprintf(share, sizeof share, "%.2f%%", 100.0 * double(t.changed) / double(t.compared));
    md << "| " << t.kind << " | " << t.group << " | " << t.compared << " | " << t.changed << " | "
       << share << " | " << t.not_drawn << " | " << t.new_violations << " | " << t.allowed
       << " |\n";
  }
  Transitions classes, visibility;
  const auto verdict = [](metrics::Conformance c) {
    return c == metrics::Conformance::kNotCompared ? std::string("n/a")
                                                   : metrics::conformance_name(c);
  };
  for (const ChangedPrimitive& c : s.changed) {
    const std::string kind = geometry::kind_name(c.kind);
    const std::string group = analysis::view_group_label(c.view_group);
    ++classes[{kind, group, verdict(c.before.conformance), verdict(c.after.conformance)}];
    if (c.before.visibility != c.after.visibility)
      ++visibility[{kind, group, metrics::visibility_name(c.before.visibility),
                    metrics::visibility_name(c.after.visibility)}];
  }
  const char* table = "| kind | group | before | after | primitives |\n"
                      "| --- | :---: | --- | --- | ---: |\n";
  if (!classes.empty()) {
    md << "\n### Class transitions of the changed primitives (exact / snapped / within-spec / "
          "violation)\n\n"
       << table;
    transition_rows(md, classes);
  }
  if (!visibility.empty()) {
    md << "\n### Visibility transitions (true-visible -> false-invisible: not drawn)\n\n" << table;
    transition_rows(md, visibility);
  }
}

}  // namespace

std::string upgrade_report_markdown(const UpgradeReportOptions& o) {
  const UpgradeFindings u = find_upgrade_changes(o);
  report::write_upgrade_summary(u.summary,
                                rundir::run_folder::upgrade_summary(o.run_dir, o.build));
  std::ostringstream md;
  md << "# Driver upgrade: what changed\n\n"
     << report::upgrade_sentences_markdown(u.summary) << "\n"
     << "Run `" << o.run_dir << "`: each platform P, the installed Mesa ("
     << mesa_versions(u.summary, false) << "), against P@" << o.build << " (Mesa "
     << mesa_versions(u.summary, true) << "). View groups: ";
  for (std::size_t i = 0; i < u.summary.groups.size(); ++i) {
    const report::UpgradeViewGroup& g = u.summary.groups[i];
    md << (i ? ", " : "") << g.label << ": FOV " << g.fov_deg << " at " << g.window << " x "
       << g.window;
  }
  md << ".\n\n[TOC]\n\n";
  // the lead picture, then one set per other finding
  for (std::size_t i = 0; i < u.shown.size(); ++i) {
    if (i == 1)
      md << "# The other findings in pictures\n\n"
         << "One picture set per distinct finding: the primitive whose lit pixels changed "
            "most.\n\n";
    md << (i ? "## " : "# ") << u.shown[i].title << "\n\n" << picture_pair(u, u.shown[i]) << "\n";
  }
  md << "# Per platform\n\n"
     << "### Changed primitives, tests and new violations per platform\n\n"
     << "| platform | installed GL_VERSION | build GL_VERSION | compared | changed | significant "
        "tests | new violations |\n| --- | --- | --- | ---: | ---: | ---: | ---: |\n";
  for (std::size_t i = 0; i < u.sides.size(); ++i) {
    const rundir::AuditDocument& a = u.sides[i].audit;
    const report::UpgradePair& p = u.summary.pairs[i];
    md << "| " << p.platform << " | " << p.installed_version << " | " << p.build_version << " | "
       << a.compared << " | " << a.changed << " | " << a.significant_tests << " of "
       << a.family_size << " | " << a.new_violations << " |\n";
  }
  for (std::size_t i = 0; i < u.sides.size(); ++i) pair_section(md, u.summary.pairs[i], u.sides[i]);
  return md.str();
}

}  // namespace ra::triage
