// Judging a bisection's drawings (see the header).
#include "triage/bisect_judging.h"

#include <algorithm>
#include <set>

#include "builds/git_command.h"
#include "triage/bisect_step.h"

namespace ra::triage {

void split_by_ends(const std::vector<BisectPrimitive>& selection, const Drawing& good,
                   const Drawing& bad, std::vector<BisectPrimitive>& judged,
                   std::vector<std::string>& dropped) {
  dropped.clear();
  for (const BisectPrimitive& p : selection) {
    const std::string l = p.label();
    if (good.hashes.at(l) == bad.hashes.at(l))
      dropped.push_back(l);
    else
      judged.push_back(p);
  }
}

std::map<std::string, uint64_t> judged_hashes(const std::vector<BisectPrimitive>& judged,
                                              const Drawing& d) {
  std::map<std::string, uint64_t> out;
  for (const BisectPrimitive& p : judged)
    if (const auto it = d.hashes.find(p.label()); it != d.hashes.end()) out.insert(*it);
  return out;
}

std::string drawing_summary(const std::vector<BisectPrimitive>& judged, const Drawing& good,
                            const Drawing& bad, const Drawing& d) {
  std::size_t like_good = 0, like_bad = 0, other = 0;
  for (const BisectPrimitive& p : judged) {
    const std::string l = p.label();
    const auto it = d.hashes.find(l);
    if (it == d.hashes.end()) continue;
    if (it->second == good.hashes.at(l))
      ++like_good;
    else if (it->second == bad.hashes.at(l))
      ++like_bad;
    else
      ++other;
  }
  return std::to_string(like_good) + " like the good ref, " + std::to_string(like_bad) +
         " like the bad ref, " + std::to_string(other) + " like neither";
}

void collect_culprits(const AttributionPlan& plan, const std::vector<std::string>& line,
                      const std::vector<BisectPrimitive>& judged, const std::string& source,
                      BisectResult& r, const std::function<void(const std::string&)>& say) {
  using builds::git;
  std::map<std::size_t, const Drawing*> drawn = {{0, &r.good.drawing},
                                                 {line.size() - 1, &r.bad.drawing}};
  for (const BisectStep& s : r.steps)
    if (s.error.empty()) drawn[s.position] = &s.drawing;
  std::map<std::size_t, Culprit> by_position;
  r.unattributed.clear();
  const auto pixels = [&](std::size_t position, const std::string& l) -> int64_t {
    const Drawing* d = drawn.at(position);
    const auto it = d->pixels.find(l);
    return it == d->pixels.end() ? -1 : it->second;
  };
  std::set<std::string> primitives;  // the plan also holds drawing times (bisect_speed.h)
  for (const BisectPrimitive& p : judged) primitives.insert(p.label());
  for (const AttributionPlan::Change& c : plan.changes()) {
    if (!primitives.count(c.label)) continue;
    if (!c.resolved) {
      Unattributed u{c.label, line[c.from], line[c.to], {}};
      for (std::size_t p : c.candidates) u.candidates.push_back(line[p]);
      r.unattributed.push_back(u);
      continue;
    }
    Culprit& k = by_position[c.to];
    k.primitives.push_back(c.label);
    k.pixels[c.label] = {pixels(c.from, c.label), pixels(c.to, c.label)};
  }
  r.culprits.clear();
  for (auto& [position, k] : by_position) {
    BisectStep info;
    info.commit = line[position];
    describe_commit(source, info);
    k.commit = info.commit;
    k.subject = info.subject;
    k.date = info.date;
    k.previous = line[position - 1];
    // "COMMIT PARENT..." : a merge names two parents or more.
    const std::string parents = git(source, {"rev-list", "--parents", "-n", "1", k.commit}).out;
    k.merge = parents.find(' ') != parents.rfind(' ');
    // In selection order.
    std::vector<std::string> ordered;
    for (const BisectPrimitive& p : judged)
      if (std::find(k.primitives.begin(), k.primitives.end(), p.label()) != k.primitives.end())
        ordered.push_back(p.label());
    k.primitives = ordered;
    r.culprits.push_back(k);
    // Not the "first bad commit:" line itself: the command prints it on stdout, and a terminal
    // shows both streams.
    say("named " + short_hash(k.commit) + " " + k.subject + ": " +
        std::to_string(k.primitives.size()) + " primitives");
  }
  if (!r.unattributed.empty())
    say(std::to_string(r.unattributed.size()) +
        " changes stay unattributed: only commits that failed to build lie between two drawn "
        "commits");
}

}  // namespace ra::triage
