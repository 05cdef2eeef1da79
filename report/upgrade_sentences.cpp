// The driver upgrade report's sentences (see the header).
#include "report/upgrade_sentences.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <tuple>

#include "rundir/run_folder.h"

namespace fs = std::filesystem;

namespace ra::report {
namespace {

// 20000 -> "20,000"
std::string grouped(std::int64_t n) {
  std::string digits = std::to_string(n < 0 ? -n : n), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return (n < 0 ? "-" : "") + out;
}

std::string plural(const std::string& kind, std::int64_t n) { return n == 1 ? kind : kind + "s"; }

// "osmesa-llvmpipe" -> {"osmesa", "llvmpipe"}; a name without a back end is all driver.
std::pair<std::string, std::string> backend_and_driver(const std::string& platform) {
  const std::size_t dash = platform.find('-');
  if (dash == std::string::npos) return {"", platform};
  return {platform.substr(0, dash), platform.substr(dash + 1)};
}

std::string backend_name(const std::string& backend) {
  static const std::map<std::string, std::string> names = {
      {"osmesa", "OSMesa"}, {"egl", "EGL"}, {"vk", "Vulkan"}, {"glx", "GLX"}};
  const auto it = names.find(backend);
  return it != names.end() ? it->second : backend;
}

// "A", "A and B", "A, B and C"
std::string and_list(const std::vector<std::string>& items) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i)
    out += (i == 0 ? "" : i + 1 == items.size() ? " and " : ", ") + items[i];
  return out;
}

// The counts of one kind over the view groups of one pair.
struct KindCounts {
  std::int64_t compared = 0, changed = 0, not_drawn = 0, newly_drawn = 0, new_violations = 0,
               fixed_violations = 0, allowed = 0;
  std::int64_t not_drawn_violations = 0;
  bool overlap_known = true;  // every stratum said its not_drawn_violations
  std::set<std::string> groups, not_drawn_groups;  // compared in; something not drawn in
  std::int64_t compared_where_not_drawn = 0;
};

// Kinds in the order the report names them: most rules broken first, then by name.
std::vector<std::pair<std::string, KindCounts>> kinds_of(const UpgradePair& p) {
  std::map<std::string, KindCounts> by_kind;
  for (const UpgradeStratum& s : p.strata) {
    KindCounts& k = by_kind[s.kind];
    k.compared += s.compared, k.changed += s.changed, k.not_drawn += s.not_drawn;
    k.newly_drawn += s.newly_drawn, k.new_violations += s.new_violations;
    k.fixed_violations += s.fixed_violations, k.allowed += s.allowed;
    if (s.not_drawn_violations < 0) k.overlap_known = false;
    else k.not_drawn_violations += s.not_drawn_violations;
    if (s.compared > 0) k.groups.insert(s.group);
    if (s.not_drawn > 0) k.not_drawn_groups.insert(s.group);
  }
  for (const UpgradeStratum& s : p.strata)
    if (by_kind[s.kind].not_drawn_groups.count(s.group))
      by_kind[s.kind].compared_where_not_drawn += s.compared;
  std::vector<std::pair<std::string, KindCounts>> out(by_kind.begin(), by_kind.end());
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
    return a.second.new_violations + a.second.not_drawn > b.second.new_violations + b.second.not_drawn;
  });
  return out;
}

// " of the FOV-30 907 x 907 views" for the groups `used` among those a kind was compared in
// ("" when it is all of them).
std::string views_phrase(const std::set<std::string>& used, const std::set<std::string>& all,
                         const std::vector<UpgradeViewGroup>& groups) {
  if (used == all) return "";
  std::map<std::string, UpgradeViewGroup> by_label;
  for (const UpgradeViewGroup& g : groups) by_label[g.label] = g;
  std::set<int> windows, fovs;
  for (const std::string& u : used) {
    const auto it = by_label.find(u);
    if (it == by_label.end()) return " of view groups " + and_list({used.begin(), used.end()});
    windows.insert(it->second.window), fovs.insert(it->second.fov_deg);
  }
  // the groups (of those compared) that share the window, or the field of view, of `used`
  std::set<std::string> same_window, same_fov;
  for (const std::string& a : all) {
    const auto it = by_label.find(a);
    if (it == by_label.end()) continue;
    if (windows.size() == 1 && it->second.window == *windows.begin()) same_window.insert(a);
    if (fovs.size() == 1 && it->second.fov_deg == *fovs.begin()) same_fov.insert(a);
  }
  const std::string window = windows.size() == 1 ? std::to_string(*windows.begin()) + " x " +
                                                       std::to_string(*windows.begin())
                                                 : "";
  const std::string fov = fovs.size() == 1 ? "FOV-" + std::to_string(*fovs.begin()) : "";
  if (!window.empty() && used == same_window) return " of the " + window + " views";
  if (!fov.empty() && used == same_fov) return " of the " + fov + " views";
  if (!window.empty() && !fov.empty()) return " of the " + fov + " " + window + " views";
  return " of view groups " + and_list({used.begin(), used.end()});
}

// How many of a kind's new violations are among its primitives not drawn: "595 of them not drawn
// at all", "all 3 not drawn at all", "none of them among the 12 not drawn".
std::string among_not_drawn(const KindCounts& k) {
  const std::int64_t n = k.not_drawn_violations;
  if (n == 0) return "none of them among the " + grouped(k.not_drawn) + " not drawn";
  if (n < k.new_violations) return grouped(n) + " of them not drawn at all";
  return k.new_violations == 1 ? "not drawn at all" : "all " + grouped(n) + " not drawn at all";
}

// What changed in one pair, clause by clause ("stops drawing ...", "799 lines break ...").
std::vector<std::string> pair_clauses(const UpgradePair& p,
                                      const std::vector<UpgradeViewGroup>& groups) {
  std::vector<std::string> out;
  for (const auto& [kind, k] : kinds_of(p)) {
    bool named = false;  // this kind already said: "other" for the rest
    if (k.not_drawn > 0) {
      out.push_back("stops drawing " + grouped(k.not_drawn) + " of " +
                    grouped(k.compared_where_not_drawn) + " " +
                    plural(kind, k.compared_where_not_drawn) +
                    views_phrase(k.not_drawn_groups, k.groups, groups));
      named = true;
    }
    if (k.newly_drawn > 0)
      out.push_back("now draws " + grouped(k.newly_drawn) + " " + plural(kind, k.newly_drawn) +
                    " that were not drawn");
    // of those breaking the rules, how many are among the not drawn (see the header)
    const bool nest = k.overlap_known && k.not_drawn > 0;
    if (k.new_violations > 0)
      out.push_back(grouped(k.new_violations) + " " + plural(kind, k.new_violations) +
                    (k.new_violations == 1 ? " breaks" : " break") + " GL's " + kind + " rules" +
                    (nest ? ", " + among_not_drawn(k) : ""));
    if (k.fixed_violations > 0)
      out.push_back(grouped(k.fixed_violations) + " " + plural(kind, k.fixed_violations) +
                    " no longer " + (k.fixed_violations == 1 ? "breaks" : "break") + " GL's " +
                    kind + " rules");
    named = named || k.new_violations > 0 || k.fixed_violations > 0;
    if (k.allowed > 0)
      out.push_back(grouped(k.allowed) + (named ? " other " : " of " + grouped(k.compared) + " ") +
                    plural(kind, named ? k.allowed : k.compared) +
                    (k.allowed == 1 ? " lights" : " light") + " other pixels, as GL allows");
    const std::int64_t rest = k.changed - k.new_violations - k.fixed_violations - k.allowed;
    // the not drawn that break no new rule are among these
    const std::int64_t rest_not_drawn = nest ? k.not_drawn - k.not_drawn_violations : 0;
    if (rest > 0)
      out.push_back(grouped(rest) + " more " + plural(kind, rest) +
                    (rest == 1 ? " changes" : " change") +
                    " where GL's rules were not judged or already broken" +
                    (rest_not_drawn == 0      ? ""
                     : rest_not_drawn == rest ? (rest == 1 ? " (not drawn)" : " (all not drawn)")
                                              : " (" + grouped(rest_not_drawn) +
                                                    " of them not drawn)"));
  }
  return out;
}

// "OSMesa", "EGL" of each pair, in order.
std::vector<std::string> backends_of(const std::vector<const UpgradePair*>& pairs) {
  std::vector<std::string> out;
  for (const UpgradePair* p : pairs)
    out.push_back(backend_name(backend_and_driver(p->platform).first));
  return out;
}

bool same_findings(const UpgradePair& a, const UpgradePair& b) {
  if (a.fingerprint != b.fingerprint || a.strata.size() != b.strata.size()) return false;
  for (std::size_t i = 0; i < a.strata.size(); ++i) {
    const UpgradeStratum &x = a.strata[i], &y = b.strata[i];
    if (std::tie(x.kind, x.group, x.compared, x.changed, x.not_drawn, x.newly_drawn,
                 x.new_violations, x.fixed_violations, x.allowed, x.not_drawn_violations) !=
        std::tie(y.kind, y.group, y.compared, y.changed, y.not_drawn, y.newly_drawn,
                 y.new_violations, y.fixed_violations, y.allowed, y.not_drawn_violations))
      return false;
  }
  return true;
}

std::int64_t changed_of(const UpgradePair& p) {
  std::int64_t n = 0;
  for (const UpgradeStratum& s : p.strata) n += s.changed;
  return n;
}

std::int64_t broken_of(const UpgradePair& p) {
  std::int64_t n = 0;
  for (const UpgradeStratum& s : p.strata) n += s.new_violations + s.not_drawn;
  return n;
}

// "llvmpipe 25.0.7" (the build's Mesa version, else "@BUILD"), "... through OSMesa and EGL" when
// the driver's pairs fall in more than one class.
std::string driver_label(const std::string& driver, const std::vector<const UpgradePair*>& c,
                         const std::string& build, bool several_classes) {
  const std::string version = mesa_version(c.front()->build_version);
  std::string label = driver + " " + (version.empty() ? "@" + build : version);
  if (several_classes) label += " through " + and_list(backends_of(c));
  return label;
}

// One driver's part of the sentence, over its pairs (one per back end).
std::string driver_part(const std::string& driver, const std::vector<const UpgradePair*>& pairs,
                        const std::string& build, const std::vector<UpgradeViewGroup>& groups) {
  bool any = false;
  for (const UpgradePair* p : pairs) any = any || changed_of(*p) > 0;
  if (!any) return driver + " unchanged";
  // pairs with the same findings, in the order of the summary
  std::vector<std::vector<const UpgradePair*>> classes;
  for (const UpgradePair* p : pairs) {
    auto it = std::find_if(classes.begin(), classes.end(),
                           [&](const auto& c) { return same_findings(*c.front(), *p); });
    if (it == classes.end()) classes.push_back({p});
    else it->push_back(p);
  }
  std::vector<std::string> parts;
  for (const auto& c : classes) {
    const std::vector<std::string> backends = backends_of(c);
    const std::string label = driver_label(driver, c, build, classes.size() > 1);
    const std::vector<std::string> clauses = pair_clauses(*c.front(), groups);
    if (clauses.empty()) {
      parts.push_back(label + " unchanged");
      continue;
    }
    std::string s = label + (clauses.front().rfind("stops", 0) == 0 ||
                                     clauses.front().rfind("now", 0) == 0
                                 ? " "
                                 : ": ");
    for (std::size_t i = 0; i < clauses.size(); ++i) s += (i ? "; " : "") + clauses[i];
    if (classes.size() == 1 && c.size() > 1) s += " (identical through " + and_list(backends) + ")";
    parts.push_back(s);
  }
  std::string out;
  for (std::size_t i = 0; i < parts.size(); ++i) out += (i ? "; " : "") + parts[i];
  return out;
}

// Drawing time: what the second sentence says (see the header).

bool faster_or_slower(const UpgradeTime& t) {
  return t.verdict == "faster" || t.verdict == "slower";
}

// The groups a pair calls faster or slower, (kind, group) -> verdict: what its clauses say.
std::map<std::pair<std::string, std::string>, std::string> time_findings(const UpgradePair& p) {
  std::map<std::pair<std::string, std::string>, std::string> out;
  for (const UpgradeTime& t : p.speed)
    if (faster_or_slower(t)) out[{t.kind, t.group}] = t.verdict;
  return out;
}

// "the triangles of the FOV-150 907 x 907 views 22% faster (95%: 20-25%)": the groups `used` in
// which every pair of `c` draws `kind` `verdict` ("faster" or "slower"), with the range of their
// estimates and an interval holding each of theirs, in whole percents (the interval rounded
// outwards).
std::string time_clause(const std::string& kind, const std::string& verdict,
                        const std::set<std::string>& used, const std::vector<const UpgradePair*>& c,
                        const std::vector<UpgradeViewGroup>& groups) {
  const bool faster = verdict == "faster";
  double est_low = INFINITY, est_high = -INFINITY, low = INFINITY, high = -INFINITY;
  for (const UpgradePair* p : c)
    for (const UpgradeTime& u : p->speed) {
      if (u.kind != kind || !used.count(u.group)) continue;
      // percent of the installed time: faster 1 - ratio, slower ratio - 1
      const double est = 100 * (faster ? 1 - u.ratio : u.ratio - 1);
      est_low = std::min(est_low, est), est_high = std::max(est_high, est);
      low = std::min(low, 100 * (faster ? 1 - u.high : u.low - 1));
      high = std::max(high, 100 * (faster ? 1 - u.low : u.high - 1));
    }
  const auto whole = [](double v) { return std::to_string(static_cast<long long>(v)); };
  // outwards, but not past a whole number that only floating point missed (100 * (1 - 0.8))
  constexpr double kSlack = 1e-9;
  const std::string a = whole(std::round(est_low)), b = whole(std::round(est_high));
  const std::string lo = whole(std::floor(low + kSlack)), hi = whole(std::ceil(high - kSlack));
  std::set<std::string> timed;  // the groups this kind was timed in
  for (const UpgradeTime& u : c.front()->speed)
    if (u.kind == kind) timed.insert(u.group);
  return "the " + plural(kind, 2) + views_phrase(used, timed, groups) + " " +
         (a == b ? a : a + "-" + b) + "% " + verdict + " (95%: " + (lo == hi ? lo : lo + "-" + hi) +
         "%)";
}

// One driver's clauses on drawing time, over its timed pairs: one per class of pairs that call
// the same groups faster and slower, none for a class that calls none. A driver audited through
// more than one back end names those of each clause ("llvmpipe 25.0.7 through OSMesa and EGL
// draws ..."): a clause without them would read as true of every back end, timed or not.
std::vector<std::string> driver_time_parts(const std::string& driver,
                                           const std::vector<const UpgradePair*>& pairs,
                                           const std::string& build,
                                           const std::vector<UpgradeViewGroup>& groups) {
  std::vector<std::vector<const UpgradePair*>> classes;
  for (const UpgradePair* p : pairs) {
    if (!p->timed) continue;
    auto it = std::find_if(classes.begin(), classes.end(), [&](const auto& c) {
      return time_findings(*c.front()) == time_findings(*p);
    });
    if (it == classes.end())
      classes.push_back({p});
    else
      it->push_back(p);
  }
  std::vector<std::string> parts;
  for (const auto& c : classes) {
    // one clause per kind and verdict, over its groups, in the order of the first
    std::vector<std::pair<std::string, std::string>> order;
    std::map<std::pair<std::string, std::string>, std::set<std::string>> used;
    for (const UpgradeTime& t : c.front()->speed) {
      if (!faster_or_slower(t)) continue;
      if (!used.count({t.kind, t.verdict})) order.push_back({t.kind, t.verdict});
      used[{t.kind, t.verdict}].insert(t.group);
    }
    std::vector<std::string> clauses;
    for (const auto& [kind, verdict] : order)
      clauses.push_back(time_clause(kind, verdict, used[{kind, verdict}], c, groups));
    if (clauses.empty()) continue;
    parts.push_back(driver_label(driver, c, build, pairs.size() > 1) + " draws " +
                    and_list(clauses));
  }
  return parts;
}

// The sentence on drawing time, "" where no pair was timed.
std::string time_sentence(const UpgradeSummary& summary, const std::vector<std::string>& drivers,
                          const std::map<std::string, std::vector<const UpgradePair*>>& pairs_of) {
  std::vector<std::string> parts;
  for (const std::string& d : drivers)
    for (std::string& part : driver_time_parts(d, pairs_of.at(d), summary.build, summary.groups))
      parts.push_back(std::move(part));
  const bool named = !parts.empty();
  std::int64_t same = 0, unknown = 0;
  for (const UpgradePair& p : summary.pairs)
    for (const UpgradeTime& t : p.speed)
      same += t.verdict == "same", unknown += t.verdict == "unknown";
  if (same > 0)
    parts.push_back(std::string(named ? "other " : "") +
                    "drawing times unchanged or not measurably different");
  if (unknown > 0)
    parts.push_back("the drawing time of " + grouped(unknown) + " " + plural("group", unknown) +
                    " could not be judged at this noise");
  if (parts.empty()) return "";
  std::string out;
  for (std::size_t i = 0; i < parts.size(); ++i) out += (i ? "; " : "") + parts[i];
  // a driver's name keeps its case ("llvmpipe"); the sentence's own words start with a capital
  if (!named) out[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(out[0])));
  return out + ".";
}

}  // namespace

std::string mesa_version(const std::string& gl_version) {
  const std::size_t at = gl_version.find("Mesa ");
  if (at == std::string::npos) return "";
  std::size_t end = at + 5;
  while (end < gl_version.size() && gl_version[end] != ' ' && gl_version[end] != ')') ++end;
  std::string v = gl_version.substr(at + 5, end - at - 5);
  // a distribution's revision ("-2~bpo12+1") is not Mesa's version; "-devel" is
  const std::size_t dash = v.find('-');
  if (dash != std::string::npos && dash + 1 < v.size() && std::isdigit(static_cast<unsigned char>(v[dash + 1])))
    v.erase(dash);
  return v;
}

std::string upgrade_sentences(const UpgradeSummary& summary) {
  if (summary.pairs.empty()) return "no platform was audited.";
  // drivers in the order of the summary's pairs
  std::vector<std::string> drivers;
  std::map<std::string, std::vector<const UpgradePair*>> pairs_of;
  for (const UpgradePair& p : summary.pairs) {
    const std::string driver = backend_and_driver(p.platform).second;
    if (!pairs_of.count(driver)) drivers.push_back(driver);
    pairs_of[driver].push_back(&p);
  }
  // the drivers that broke most rules first, unchanged ones last
  const auto weight = [&](const std::string& d) {
    std::int64_t broken = 0, changed = 0;
    for (const UpgradePair* p : pairs_of[d]) broken += broken_of(*p), changed += changed_of(*p);
    return std::make_pair(broken, changed);
  };
  std::stable_sort(drivers.begin(), drivers.end(),
                   [&](const std::string& a, const std::string& b) { return weight(a) > weight(b); });
  std::string out;
  for (std::size_t i = 0; i < drivers.size(); ++i)
    out += (i ? "; " : "") + driver_part(drivers[i], pairs_of[drivers[i]], summary.build,
                                         summary.groups);
  const std::string time = time_sentence(summary, drivers, pairs_of);
  return out + "." + (time.empty() ? "" : " " + time);
}

std::vector<rundir::BisectionDocument> find_bisections(const std::string& run_dir) {
  namespace folder = rundir::run_folder;
  std::vector<fs::path> candidates = {
      folder::bisection(folder::bisect(run_dir)),
      folder::bisection(folder::bisect(fs::absolute(run_dir).parent_path().string()))};
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(run_dir, ec))
    if (e.is_directory() && e.path().filename().string().rfind("audit-", 0) == 0)
      candidates.push_back(folder::bisection(folder::bisect(e.path().string())));
  std::sort(candidates.begin() + 2, candidates.end());
  std::vector<rundir::BisectionDocument> out;
  std::set<fs::path> seen;
  const fs::path run = fs::weakly_canonical(run_dir, ec);
  for (const fs::path& c : candidates) {
    if (!fs::exists(c) || !seen.insert(fs::weakly_canonical(c, ec)).second) continue;
    std::optional<rundir::BisectionDocument> b = rundir::read_bisection_document_if_any(c.string());
    if (!b) continue;
    // a bisection beside the run is of this run only if it says so (or says no run)
    if (!b->run.empty() && fs::weakly_canonical(b->run, ec) != run) continue;
    out.push_back(std::move(*b));
  }
  return out;
}

std::string bisection_sentence(const rundir::BisectionDocument& b) {
  const auto selected = std::int64_t(b.selected);
  std::string s = "Bisection" + (b.platform.empty() ? "" : " of " + b.platform) + " (`" + b.path +
                  "`, " + grouped(selected) + " " + plural("primitive", selected) + ")";
  if (b.culprits.empty())
    return s + (b.complete ? ": no commit changed them." : ": no first bad commit named yet.");
  s += ": ";
  for (std::size_t i = 0; i < b.culprits.size(); ++i) {
    const rundir::BisectionCulprit& c = b.culprits[i];
    const auto changed = std::int64_t(c.primitives.size());
    s += (i ? "; " : "") + std::string("first bad commit `") + c.commit.substr(0, 12) + "` \"" +
         c.subject + "\" (" + grouped(changed) + " " + plural("primitive", changed) + ")";
  }
  return s + (b.complete ? "." : "; not every change is attributed yet.");
}

std::string upgrade_sentences_markdown(const UpgradeSummary& summary) {
  std::string out = "**" + upgrade_sentences(summary) + "**\n";
  for (const rundir::BisectionDocument& b : find_bisections(summary.run_dir))
    out += "\n" + bisection_sentence(b) + "\n";
  return out;
}

}  // namespace ra::report
