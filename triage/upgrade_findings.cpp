// What the driver upgrade report says (see the header).
#include "triage/upgrade_findings.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>
#include <tuple>

#include "analysis/run_records.h"
#include "audit/run_identity.h"
#include "report/upgrade_sentences.h"
#include "rundir/run_folder.h"
#include "util/errors.h"
#include "util/fnv1a.h"
#include "util/shell_quote.h"

namespace ra::triage {
namespace {

using audit::ChangeCategory;
using audit::ChangedPrimitive;

// The audit of p against q, checked to be that pair's.
rundir::AuditDocument audit_of(const UpgradeReportOptions& o, const std::string& p,
                              const std::string& q) {
  const std::string dir = rundir::run_folder::named_audit(o.run_dir, p + o.audit_suffix);
  rundir::AuditDocument a;
  try {
    a = rundir::read_audit_document(dir);
  } catch (const util::UserError& e) {
    throw util::UserError(std::string(e.what()) + "; the audit of " + p + " against " + q +
                          " is made by `renderaudit audit " +
                          util::shell_command({o.run_dir, "--between", p, q, "--out", dir}) + "`");
  }
  if (!a.compares(p, q))
    throw util::UserError(a.path + ": 'pairs' does not compare " + p + " with " + q +
                          ": this is another audit's folder (give the right --audit-suffix)");
  return a;
}

// The audit's flakes of this pair, left out as the audit leaves them out.
std::vector<ChangedPrimitive> without_flakes(const std::vector<ChangedPrimitive>& changed,
                                             const UpgradeSide& s) {
  std::set<std::tuple<std::string, int, uint64_t>> flakes;
  for (const rundir::AuditedFlake& f : s.audit.flakes)
    if (f.baseline_platform == s.platform && f.platform == s.build_platform)
      flakes.insert({f.kind, f.view, f.index});
  std::vector<ChangedPrimitive> out;
  for (const ChangedPrimitive& c : changed)
    if (!flakes.count({geometry::kind_name(c.kind), c.view, c.index})) out.push_back(c);
  return out;
}

// The changed primitives and their pixels after: equal fingerprints, the same change.
std::string fingerprint(std::vector<ChangedPrimitive> changed) {
  std::sort(changed.begin(), changed.end(), [](const auto& a, const auto& b) {
    return std::tuple(std::string(geometry::kind_name(a.kind)), a.view, a.index) <
           std::tuple(std::string(geometry::kind_name(b.kind)), b.view, b.index);
  });
  util::Fnv1a64 h;
  for (const ChangedPrimitive& c : changed)
    h.add(std::string(geometry::kind_name(c.kind)) + " " + std::to_string(c.view) + " " +
          std::to_string(c.index) + " " + metrics::status_name(c.after.status) + " " +
          metrics::visibility_name(c.after.visibility) + " " + std::to_string(c.after.pixel_hash) +
          "\n");
  return util::hex64(h.value);
}

// The counts of one pair as the summary keeps them, by kind and view group label.
std::vector<report::UpgradeStratum> strata_of(const std::vector<audit::ChangeCounts>& counts,
                                              std::size_t pair) {
  std::vector<report::UpgradeStratum> out;
  for (const audit::ChangeCounts& c : counts)
    if (c.pair == pair)
      out.push_back({geometry::kind_name(c.kind), analysis::view_group_label(c.view_group),
                     std::int64_t(c.compared), std::int64_t(c.changed),
                     std::int64_t(c.not_drawn), std::int64_t(c.newly_drawn),
                     std::int64_t(c.new_violations), std::int64_t(c.fixed_violations),
                     std::int64_t(c.allowed), std::int64_t(c.not_drawn_violations)});
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
    return std::tie(a.kind, a.group) < std::tie(b.kind, b.group);
  });
  return out;
}

// The drawing-time verdicts of the pair, where its audit judged drawing time.
void add_speed(report::UpgradePair& pair, const rundir::AuditDocument& a) {
  pair.timed = a.timed;
  if (!a.timed) return;
  for (const rundir::AuditedTime& t : a.speed)
    if (t.baseline_platform == pair.platform && t.platform == pair.build_platform)
      pair.speed.push_back({t.kind, t.group, t.ratio, t.low, t.high, t.verdict});
}

// The view groups of the run: label, field of view (whole degrees) and window.
std::vector<report::UpgradeViewGroup> view_groups(const rundir::Experiment& exp) {
  std::map<std::string, report::UpgradeViewGroup> by_label;
  for (const geometry::View& v : exp.views) {
    const std::string label = analysis::view_group_label(v.group);
    by_label[label] = {label, int(std::lround(v.fov_deg)), v.width};
  }
  std::vector<report::UpgradeViewGroup> out;
  for (const auto& [label, g] : by_label) out.push_back(g);
  return out;
}

bool breaks(const ChangedPrimitive& c) { return audit::new_violation(c); }

// How a picture's title counts a finding, nested as page 1 nests the counts (a not drawn
// primitive is counted on page 1 among those breaking GL's rules, or else among the "more"):
// "53 lines not drawn (52 of them breaking GL's rules)", "23 of the 75 lines that break GL's
// rules, drawn (the other 52 are not drawn)".
std::string finding_words(ChangeCategory cat, geometry::Kind kind,
                          const std::vector<ChangedPrimitive>& changed) {
  std::int64_t n = 0, both = 0, also = 0;
  for (const ChangedPrimitive& c : changed) {
    if (c.kind != kind) continue;
    const ChangeCategory cc = audit::change_category(c);
    n += cc == cat;
    both += cc == ChangeCategory::kNotDrawn && breaks(c);
    // the not drawn that page 1 counts with this finding
    also += cc == ChangeCategory::kNotDrawn && breaks(c) == (cat == ChangeCategory::kNewViolation);
  }
  const std::string k = geometry::kind_name(kind), kinds = n == 1 ? k : k + "s";
  const std::string words = category_words(cat), count = std::to_string(n);
  if (cat == ChangeCategory::kNotDrawn) {
    if (!both) return count + " " + kinds + " " + words;
    return count + " " + kinds + " " + words + " (" +
           (n == 1       ? std::string("breaking GL's rules")
            : both == n ? std::string("all breaking GL's rules")
                        : std::to_string(both) + " of them breaking GL's rules") +
           ")";
  }
  if ((cat == ChangeCategory::kNewViolation || cat == ChangeCategory::kOther) && also)
    return count + " of the " + std::to_string(n + also) + " " + k + "s " + words +
           ", drawn (the other " + std::to_string(also) + (also == 1 ? " is" : " are") +
           " not drawn)";
  // one primitive "breaks", several "break"
  std::string said = words;
  if (const std::size_t at = said.find("break "); n == 1 && at != std::string::npos)
    said.replace(at, 6, "breaks ");
  return count + " " + kinds + " " + said;
}

int64_t pixel_change(const ChangedPrimitive& c) { return std::llabs(c.after.pixels - c.before.pixels); }

// A distinct finding: the pairs of one driver that changed alike.
struct Finding {
  std::string driver;
  std::vector<std::size_t> sides;
};

// One picture set per finding: per category, most severe first, and kind, the primitive whose lit
// pixels changed most; the lead, the most striking of those breaking GL's rules, first.
std::vector<ShownPrimitive> shown_of(const UpgradeFindings& u, const std::vector<Finding>& findings,
                                     const std::string& build) {
  std::vector<ShownPrimitive> shown;
  for (const Finding& f : findings) {
    const UpgradeSide& first = u.sides[f.sides.front()];
    std::vector<std::string> backends;
    for (std::size_t s : f.sides) backends.push_back(backend_label(u.sides[s].platform));
    std::string joined;
    for (std::size_t i = 0; i < backends.size(); ++i) joined += (i ? " and " : "") + backends[i];
    std::string version = report::mesa_version(u.summary.pairs[f.sides.front()].build_version);
    if (version.empty()) version = "@" + build;
    const std::string through = (f.sides.size() > 1 ? "identical through " : "through ") + joined;
    for (ChangeCategory cat : {ChangeCategory::kNotDrawn, ChangeCategory::kNewViolation,
                               ChangeCategory::kFixed, ChangeCategory::kOther,
                               ChangeCategory::kAllowed})
      for (geometry::Kind kind : {geometry::Kind::kLine, geometry::Kind::kPoint,
                                  geometry::Kind::kTriangle}) {  // by name
        const ChangedPrimitive* worst = nullptr;
        for (const ChangedPrimitive& c : first.changed) {
          if (c.kind != kind || audit::change_category(c) != cat) continue;
          if (!worst || std::tuple(pixel_change(c), -c.view, -int64_t(c.index)) >
                            std::tuple(pixel_change(*worst), -worst->view, -int64_t(worst->index)))
            worst = &c;
        }
        if (!worst) continue;
        shown.push_back({cat,
                         f.driver + " " + version + ", " + through + ": " +
                             finding_words(cat, kind, first.changed) + "; the worst, " +
                             geometry::kind_name(kind) + " " + std::to_string(worst->index) +
                             " of view " + std::to_string(worst->view),
                         f.sides.front(), *worst});
      }
  }
  std::stable_sort(shown.begin(), shown.end(),
                   [](const auto& a, const auto& b) { return a.category < b.category; });
  std::size_t lead = shown.size();
  for (std::size_t i = 0; i < shown.size(); ++i) {
    const ChangeCategory c = shown[i].category;
    if (c != ChangeCategory::kNotDrawn && c != ChangeCategory::kNewViolation) continue;
    if (lead == shown.size() || pixel_change(shown[i].primitive) > pixel_change(shown[lead].primitive))
      lead = i;
  }
  if (lead < shown.size()) std::rotate(shown.begin(), shown.begin() + long(lead), shown.begin() + long(lead) + 1);
  return shown;
}

}  // namespace

const char* category_words(ChangeCategory c) {
  switch (c) {
    case ChangeCategory::kNotDrawn:
      return "not drawn";
    case ChangeCategory::kNewViolation:
      return "that break GL's rules";
    case ChangeCategory::kFixed:
      return "that no longer break GL's rules";
    case ChangeCategory::kOther:
      return "changed where GL's rules were not judged or already broken";
    case ChangeCategory::kAllowed:
      return "lighting other pixels, as GL allows";
  }
  return "";
}

std::string backend_label(const std::string& platform) {
  static const std::map<std::string, std::string> names = {
      {"osmesa", "OSMesa"}, {"egl", "EGL"}, {"vk", "Vulkan"}, {"glx", "GLX"}};
  const std::string backend = platform.substr(0, platform.find('-'));
  const auto it = names.find(backend);
  return it != names.end() ? it->second : backend;
}

UpgradeFindings find_upgrade_changes(const UpgradeReportOptions& o) {
  if (o.platforms.empty()) throw util::UserError("the upgrade report needs a platform");
  const audit::RunIdentity run = audit::load_run_identity(o.run_dir);
  UpgradeFindings u;
  u.summary.run_dir = o.run_dir;
  u.summary.build = o.build;
  u.summary.groups = view_groups(run.experiment);
  std::vector<audit::PlatformPair> pairs;
  for (const std::string& p : o.platforms) {
    const std::string q = p + "@" + o.build;
    u.sides.push_back({p, q, audit_of(o, p, q), {}});
    pairs.push_back({p, q});
  }
  // the audit's own comparison, its flakes left out as it leaves them out
  audit::PrimitiveComparison cmp = audit::compare_primitives(o.run_dir, o.run_dir, pairs);
  std::vector<std::vector<ChangedPrimitive>> by_pair(pairs.size());
  for (const ChangedPrimitive& c : cmp.changed) by_pair[c.pair].push_back(c);
  cmp.changed.clear();
  for (std::size_t i = 0; i < u.sides.size(); ++i) {
    u.sides[i].changed = without_flakes(by_pair[i], u.sides[i]);
    for (ChangedPrimitive c : u.sides[i].changed) cmp.changed.push_back(c);
  }
  const std::vector<audit::ChangeCounts> counts = audit::count_changes(cmp);

  std::vector<Finding> findings;
  std::map<std::string, std::size_t> finding_of;  // driver, fingerprint and counts -> finding
  for (std::size_t i = 0; i < u.sides.size(); ++i) {
    const UpgradeSide& s = u.sides[i];
    report::UpgradePair pair{s.platform,
                             s.build_platform,
                             audit::driver_of(run, s.platform).version,
                             audit::driver_of(run, s.build_platform).version,
                             fingerprint(s.changed),
                             strata_of(counts, i),
                             false,
                             {}};
    add_speed(pair, s.audit);
    const std::size_t dash = s.platform.find('-');
    const std::string driver = dash == std::string::npos ? "" : s.platform.substr(dash + 1);
    report::UpgradeSummary one;
    one.pairs.push_back(pair);
    const std::string key = driver + "\n" + pair.fingerprint + "\n" +
                            report::upgrade_summary_json(one)["pairs"][0]["strata"].dump();
    const auto [it, added] = finding_of.emplace(key, findings.size());
    if (added) findings.push_back({driver, {}});
    findings[it->second].sides.push_back(i);
    u.summary.pairs.push_back(std::move(pair));
  }
  u.shown = shown_of(u, findings, o.build);
  return u;
}

}  // namespace ra::triage
