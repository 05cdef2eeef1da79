// The primitives a bisection draws (see the header).
#include "triage/bisect_selection.h"

#include <algorithm>
#include <cstdlib>
#include <map>
#include <tuple>

#include "audit/audit_compare.h"
#include "rundir/run_experiment.h"
#include "rundir/manifest.h"
#include "rundir/run_folder.h"
#include "util/errors.h"

namespace ra::triage {
namespace {

std::string group_letter(int g) { return g >= 0 && g < 26 ? std::string(1, char('A' + g)) : "?"; }

// The platforms a run drew (its experiment, less what `run --platform` left out), to name a
// platform that is not among them.
void require_platform(const std::string& run, const std::string& platform, const char* option) {
  std::vector<std::string> drawn = rundir::load_run_experiment(run).platforms;
  const rundir::RunManifest m =
      rundir::read_manifest_file_or_empty(rundir::run_folder::manifest(run));
  if (m.platforms_run) drawn = *m.platforms_run;
  if (std::find(drawn.begin(), drawn.end(), platform) != drawn.end()) return;
  std::string have;
  for (const std::string& p : drawn) have += (have.empty() ? "" : ", ") + p;
  throw util::UserError(std::string("bisect: ") + option + " names platform '" + platform +
                        "', which " + run + " did not draw (it has: " + have + ")");
}

}  // namespace

Selection select_primitives(const BisectOptions& o) {
  Selection sel;
  if (!o.primitives.empty()) {
    for (const std::string& p : o.primitives) sel.primitives.push_back(parse_primitive(p));
    sel.changed = sel.primitives.size();
    sel.rule = "the " + std::to_string(sel.primitives.size()) + " primitives named";
    return sel;
  }
  if (o.good_platform.empty() || o.bad_platform.empty())
    throw util::UserError(
        "bisect: name the two platforms whose records differ (--between GOOD BAD), or the "
        "primitives (--primitive KIND:VIEW:INDEX)");
  const std::string baseline = o.baseline_run.empty() ? o.run_dir : o.baseline_run;
  require_platform(baseline, o.good_platform, "--between");
  require_platform(o.run_dir, o.bad_platform, "--between");
  const audit::PrimitiveComparison c =
      audit::compare_primitives(baseline, o.run_dir, {{o.good_platform, o.bad_platform}});
  // Strata: kind, view group, conformance before and after.
  using Stratum = std::tuple<int, int, std::string, std::string>;
  std::map<Stratum, std::vector<BisectPrimitive>> strata;
  for (const audit::ChangedPrimitive& ch : c.changed) {
    if (!o.kinds.empty() &&
        std::find(o.kinds.begin(), o.kinds.end(), geometry::kind_name(ch.kind)) == o.kinds.end())
      continue;
    if (!o.views.empty() && std::find(o.views.begin(), o.views.end(), ch.view) == o.views.end())
      continue;
    if (ch.before.pixel_hash == ch.after.pixel_hash) continue;  // a verdict change only
    BisectPrimitive p{ch.kind,
                      ch.view,
                      ch.index,
                      ch.view_group,
                      ch.before.pixels,
                      ch.after.pixels,
                      metrics::conformance_name(ch.before.conformance),
                      metrics::conformance_name(ch.after.conformance)};
    strata[{int(p.kind), p.view_group, p.run_good_conformance, p.run_bad_conformance}].push_back(p);
    ++sel.changed;
  }
  if (sel.changed == 0 && o.speed.enabled) {
    sel.rule = "no primitive has other pixels on " + o.bad_platform + " than on " +
               o.good_platform + ": drawing time only";
    return sel;
  }
  if (sel.changed == 0)
    throw util::UserError("bisect: no primitive of " + o.run_dir + " has other pixels on " +
                          o.bad_platform + " than on " + o.good_platform +
                          " (with the --kind/--view filters): nothing to bisect");
  for (auto& [key, list] : strata)
    std::stable_sort(list.begin(), list.end(), [](const BisectPrimitive& a, const BisectPrimitive& b) {
      return std::llabs(a.run_bad_pixels - a.run_good_pixels) >
             std::llabs(b.run_bad_pixels - b.run_good_pixels);
    });
  // Every stratum in turn, its largest pixel change first, until the cap.
  std::vector<std::size_t> taken(strata.size(), 0);
  while (sel.primitives.size() < std::min(sel.changed, o.max_primitives)) {
    std::size_t s = 0;
    for (auto& [key, list] : strata) {
      if (taken[s] < list.size() && sel.primitives.size() < o.max_primitives)
        sel.primitives.push_back(list[taken[s]++]);
      ++s;
    }
  }
  const std::string strata_text = std::to_string(strata.size()) + " strata (kind x view group x "
                                  "conformance before and after)";
  sel.rule = sel.primitives.size() == sel.changed
                 ? "all " + std::to_string(sel.changed) + " changed primitives, in " + strata_text
                 : "a sample of " + std::to_string(sel.primitives.size()) + " of the " +
                       std::to_string(sel.changed) + " changed primitives: the " + strata_text +
                       " in turn, each giving its largest pixel change first (--max-primitives " +
                       std::to_string(o.max_primitives) + ")";
  std::string list;
  for (const auto& [key, prims] : strata) {
    const auto& [kind, group, before, after] = key;
    list += std::string(list.empty() ? "" : "; ") + geometry::kind_name(geometry::Kind(kind)) +
            "s of group " + group_letter(group) + " " + (before.empty() ? "-" : before) + " -> " +
            (after.empty() ? "-" : after) + ": " + std::to_string(prims.size());
  }
  sel.rule += " (" + list + ")";
  return sel;
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

}  // namespace ra::triage
