// junit.xml: the audit as CI test results (audit/audit_report.h). Layout:
//   <testsuites name="renderaudit audit" tests failures>
//     <testsuite name="PLATFORM" (or "P1 vs P2") tests failures>
//       (classname: "P1-vs-P2" for a pair of platforms)
//       <testcase classname="renderaudit.audit.PLATFORM" name="drivers">  GL identity (failure:
//                                                      --expect-renderer not matched)
//       <testcase classname="renderaudit.audit.PLATFORM" name="shards">   missing shards; worker
//                                                      failures that did not recur in system-out
//       <testcase classname="renderaudit.audit.PLATFORM.KIND" name="group A (views 1, 2)">
//         <properties> compared, changed, flakes, crash_timeout, missing_shards, significant_tests
//         <failure type="changed|failed" message="...">the primitives and tests</failure>
//         <system-out>flakes and significant tests, one per line</system-out>
//   (a run audited against itself: every case, drivers and shards too, <skipped
//   message="baseline established: nothing compared"/> instead of a verdict, and a group's only
//   property is its number of primitives, "primitives")
//       <testcase classname="renderaudit.audit.PLATFORM.KIND" name="conformance, group A (...)">
//         <failure type="violation">primitives breaking a GL rule the baseline did not break
#include <cstdio>
#include <sstream>

#include "audit/audit_report.h"
#include "util/xml_text.h"

namespace ra::audit {
namespace {

std::string xml(const std::string& s) { return util::xml_text(s); }

// "renderaudit.audit.PLATFORM", or "renderaudit.audit.P1-vs-P2" (CI tools read the classname as a
// dotted path: no spaces).
std::string class_prefix(const PlatformPair& p) {
  return "renderaudit.audit." +
         (p.baseline == p.current ? p.current : p.baseline + "-vs-" + p.current);
}

struct Case {
  std::string classname, name;
  std::vector<std::pair<std::string, std::string>> properties;
  std::string failure_type, failure_message, failure_text, system_out;
  std::string skipped;  // why the case was not judged ("" when it was)
};

void write_case(std::ostream& out, const Case& c) {
  out << "    <testcase classname=\"" << xml(c.classname) << "\" name=\"" << xml(c.name)
      << "\" time=\"0\">\n";
  if (!c.properties.empty()) {
    out << "      <properties>\n";
    for (const auto& [k, v] : c.properties)
      out << "        <property name=\"" << xml(k) << "\" value=\"" << xml(v) << "\"/>\n";
    out << "      </properties>\n";
  }
  if (!c.failure_type.empty())
    out << "      <failure type=\"" << xml(c.failure_type) << "\" message=\""
        << xml(c.failure_message) << "\">" << xml(c.failure_text) << "</failure>\n";
  if (!c.skipped.empty()) out << "      <skipped message=\"" << xml(c.skipped) << "\"/>\n";
  if (!c.system_out.empty()) out << "      <system-out>" << xml(c.system_out) << "</system-out>\n";
  out << "    </testcase>\n";
}

std::string group_name(const GroupOutcome& g) {
  std::string views;
  for (int v : g.views) views += (views.empty() ? "" : ", ") + std::to_string(v);
  return "group " + g.label + (g.views.size() == 1 ? " (view " : " (views ") + views + ")";
}

Case group_case(const AuditResult& r, const GroupOutcome& g) {
  Case c;
  c.classname = class_prefix(r.pairs[g.pair]) + "." + geometry::kind_name(g.kind);
  c.name = group_name(g);
  c.properties = {{"compared", std::to_string(g.compared)},
                  {"changed", std::to_string(g.changed)},
                  {"flakes", std::to_string(g.flakes)},
                  {"crash_timeout", std::to_string(g.failed)},
                  {"missing_shards", std::to_string(g.missing_shards)},
                  {"significant_tests", std::to_string(g.significant_tests)}};
  std::ostringstream text, sysout;
  auto in_group = [&](std::size_t pair, geometry::Kind kind, int group) {
    return pair == g.pair && kind == g.kind && group == g.view_group;
  };
  for (const ChangedPrimitive& p : r.primitives.changed) {
    if (!in_group(p.pair, p.kind, p.view_group)) continue;
    std::ostringstream line;
    line << geometry::kind_name(p.kind) << " view " << p.view << " index " << p.index << ": pixels "
         << p.before.pixels << " -> " << p.after.pixels << ", " << headline_metric(p.kind) << " "
         << format_number(p.before.metric, 6) << " -> " << format_number(p.after.metric, 6) << " ("
         << recheck_name(p.recheck) << "); " << show_command(r, p) << "\n";
    (p.recheck == Recheck::kFlake ? sysout : text)
        << (p.recheck == Recheck::kFlake ? "flake: " : "") << line.str();
  }
  for (const FailedPrimitive& f : r.primitives.failed)
    if (in_group(f.pair, f.kind, f.view_group))
      text << metrics::status_name(f.status) << ": " << f.side << " " << f.platform << " view "
           << f.view << " index " << f.index << "\n";
  for (const MissingShard& m : r.missing)
    if (m.kind == g.kind && m.view_group == g.view_group &&
        m.platform == (m.side == "baseline" ? r.pairs[g.pair].baseline : r.pairs[g.pair].current))
      text << "missing shard: " << m.side << " " << m.id << ": " << m.reason << "\n";
  for (const DistributionComparison& d : r.distributions.comparisons)
    for (const DistributionTest& t : d.tests)
      if (t.significant && in_group(d.pair, geometry::Kind(int(d.kind)), d.view_group))
        sysout << "significant: " << analysis::kind_metrics(d.kind)[d.metric].column << " "
               << t.test << " (" << t.data << ") p = " << format_number(t.outcome.p_value, 3)
               << ", Holm p = " << format_number(t.p_adjusted, 3) << "; median "
               << format_number(d.median_before) << " -> " << format_number(d.median_after)
               << ", IQR " << format_number(d.iqr_before) << " -> " << format_number(d.iqr_after)
               << "\n";
  const Verdict v = g.verdict();
  if (v != Verdict::kUnchanged) {
    c.failure_type = verdict_name(v);
    c.failure_message = v == Verdict::kFailed
                            ? std::to_string(g.failed) + " crash/timeout record(s), " +
                                  std::to_string(g.missing_shards) + " missing shard(s), " +
                                  std::to_string(g.rerender_failures) + " failed re-render(s)"
                            : std::to_string(g.changed) + " primitive(s) changed, " +
                                  std::to_string(g.significant_tests) + " significant test(s)";
    c.failure_text = text.str();
  }
  c.system_out = sysout.str();
  return c;
}

// The group's conformance case: fails when primitives break a GL rasterization rule that their
// baseline records did not break (metrics/conformance.h).
Case conformance_case(const AuditResult& r, const GroupOutcome& g) {
  Case c;
  c.classname = class_prefix(r.pairs[g.pair]) + "." + geometry::kind_name(g.kind);
  c.name = "conformance, " + group_name(g);
  c.properties = {{"new_violations", std::to_string(g.new_violations)}};
  if (g.new_violations == 0) return c;
  std::ostringstream text;
  for (const ChangedPrimitive& p : r.primitives.changed)
    if (p.pair == g.pair && p.kind == g.kind && p.view_group == g.view_group &&
        p.recheck != Recheck::kFlake && new_violation(p))
      text << geometry::kind_name(p.kind) << " view " << p.view << " index " << p.index << ": "
           << p.after.violating_pixels << " violating pixel(s); " << show_command(r, p) << "\n";
  c.failure_type = "violation";
  c.failure_message = std::to_string(g.new_violations) +
                      " primitive(s) break a GL rasterization rule the baseline did not break";
  c.failure_text = text.str();
  return c;
}

// One case per timed pair, kind and view group: fails when the group draws slower (a skipped
// case under --speed-warn-only, with the same message); faster, same and unknown pass, saying so.
Case speed_case(const AuditResult& r, const SpeedComparison& s) {
  Case c;
  c.classname = class_prefix(r.pairs[s.pair]) + "." + geometry::kind_name(s.kind);
  c.name = "drawing time, group " + s.group;
  auto number = [](double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", v);
    return std::string(text);
  };
  c.properties = {{"verdict", speed_verdict_name(s.verdict)},
                  {"ratio", number(s.ratio)},
                  {"low", number(s.low)},
                  {"high", number(s.high)},
                  {"primitives", std::to_string(s.n)},
                  {"repeats", std::to_string(s.repeats)}};
  const std::string message = "draws " + std::string(geometry::kind_name(s.kind)) +
                              "s of group " + s.group + " " + speed_verdict_name(s.verdict) + ": " +
                              number(s.ratio) + "x [" + number(s.low) + ", " + number(s.high) +
                              "], band " + number(s.band) + "x";
  if (s.verdict == SpeedVerdict::kSlower) {
    if (r.speed.options.warn_only) {
      c.skipped = "slower, a warning only (--speed-warn-only): " + message;
    } else {
      c.failure_type = "slower";
      c.failure_message = message;
      c.failure_text = message + "\n";
    }
  } else {
    c.system_out = message + (s.reason.empty() ? "" : " (" + s.reason + ")") + "\n";
  }
  return c;
}

}  // namespace

std::string audit_junit(const AuditResult& r) {
  const std::vector<GroupOutcome> groups = group_outcomes(r);
  std::vector<std::vector<Case>> suites(r.pairs.size());
  for (std::size_t p = 0; p < r.pairs.size(); ++p) {
    const std::string cls = class_prefix(r.pairs[p]);
    Case drivers{cls, "drivers", {}, "", "", "", "", ""};
    drivers.properties = {{"baseline_renderer", r.baseline_drivers[p].renderer},
                          {"baseline_version", r.baseline_drivers[p].version},
                          {"current_renderer", r.current_drivers[p].renderer},
                          {"current_version", r.current_drivers[p].version}};
    for (const auto& m : r.renderer_mismatches)
      if (m.rfind(r.pairs[p].current + ": ", 0) == 0)
        drivers.failure_type = "failed", drivers.failure_message = m,
        drivers.failure_text += m + "\n";
    suites[p].push_back(drivers);
    // Shards: missing ones fail (their group's case names them too); worker failures that did not
    // recur are reported in system-out.
    Case shards{cls, "shards", {}, "", "", "", "", ""};
    auto of_pair = [&](const std::string& side, const std::string& platform) {
      return platform == (side == "baseline" ? r.pairs[p].baseline : r.pairs[p].current);
    };
    std::size_t missing = 0;
    for (const MissingShard& m : r.missing)
      if (of_pair(m.side, m.platform))
        ++missing,
            shards.failure_text += "missing: " + m.side + " " + m.id + ": " + m.reason + "\n";
    for (const ManifestFailure& m : r.manifest_failures) {
      if (!of_pair(m.side, m.platform)) continue;
      const std::string line =
          m.side + " " + m.shard + " (" + failure_outcome_name(m.outcome) + "): " + m.reason + "\n";
      if (m.outcome == FailureOutcome::kUnknown)
        ++missing, shards.failure_text += line;
      else
        shards.system_out += line;
    }
    if (missing)
      shards.failure_type = "failed",
      shards.failure_message = std::to_string(missing) + " shard(s) failed";
    suites[p].push_back(shards);
  }
  for (const GroupOutcome& g : groups) {
    suites[g.pair].push_back(group_case(r, g));
    suites[g.pair].push_back(conformance_case(r, g));
  }
  for (const SpeedComparison& s : r.speed.comparisons) suites[s.pair].push_back(speed_case(r, s));
  // A run against itself judges nothing: every case is skipped (drivers and shards too: their
  // failures would have made the verdict "failed"), with only the primitives recorded as data.
  if (r.verdict == Verdict::kBaseline)
    for (auto& suite : suites)
      for (Case& c : suite) {
        c.skipped = verdict_text(r.verdict);
        c.failure_type.clear(), c.system_out.clear();
        if (c.name.rfind("group ", 0) == 0)  // {"compared", N} first: the primitives recorded
          c.properties = {{"primitives", c.properties.front().second}};
        else if (c.name.rfind("conformance, ", 0) == 0)
          c.properties.clear();
      }

  std::size_t tests = 0, failures = 0;
  for (const auto& s : suites)
    for (const Case& c : s) ++tests, failures += !c.failure_type.empty();
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"renderaudit audit\" "
         "tests=\""
      << tests << "\" failures=\"" << failures << "\" errors=\"0\">\n";
  for (std::size_t p = 0; p < suites.size(); ++p) {
    std::size_t f = 0, skipped = 0;
    for (const Case& c : suites[p]) f += !c.failure_type.empty(), skipped += !c.skipped.empty();
    out << "  <testsuite name=\"" << xml(r.pairs[p].label()) << "\" tests=\"" << suites[p].size()
        << "\" failures=\"" << f << "\" errors=\"0\" skipped=\"" << skipped << "\" timestamp=\""
        << xml(r.date_utc)
        << "\">\n";
    for (const Case& c : suites[p]) write_case(out, c);
    out << "  </testsuite>\n";
  }
  out << "</testsuites>\n";
  return out.str();
}

}  // namespace ra::audit
