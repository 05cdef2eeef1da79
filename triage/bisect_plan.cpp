// The shared-build attribution of changed primitives (see the header).
#include "triage/bisect_plan.h"

#include <algorithm>
#include <cmath>

namespace ra::triage {

AttributionPlan::AttributionPlan(std::size_t last) : last_(last) {}

void AttributionPlan::observe(std::size_t position, const std::map<std::string, uint64_t>& hashes) {
  observed_[position] = hashes;
  failed_.erase(position);
  for (const auto& [label, hash] : hashes) labels_.insert(label);
}

void AttributionPlan::fail(std::size_t position) {
  if (!observed_.count(position)) failed_.insert(position);
}

void AttributionPlan::forget(const std::string& label) {
  labels_.erase(label);
  for (auto& [position, hashes] : observed_) hashes.erase(label);
}

bool AttributionPlan::open(std::size_t p) const { return !observed_.count(p) && !failed_.count(p); }

std::vector<std::size_t> AttributionPlan::known_positions(const std::string& label) const {
  std::vector<std::size_t> out;
  for (const auto& [position, hashes] : observed_)
    if (hashes.count(label)) out.push_back(position);
  return out;
}

std::vector<AttributionPlan::Change> AttributionPlan::changes() const {
  std::vector<Change> out;
  for (const std::string& label : labels_) {
    const std::vector<std::size_t> known = known_positions(label);
    for (std::size_t i = 1; i < known.size(); ++i) {
      const std::size_t a = known[i - 1], b = known[i];
      const uint64_t before = observed_.at(a).at(label), after = observed_.at(b).at(label);
      if (before == after) continue;
      Change c{label, a, b, before, after, b == a + 1, {}};
      if (!c.resolved) {
        for (std::size_t p = a + 1; p < b; ++p)
          if (!open(p)) c.candidates.push_back(p);
        c.candidates.push_back(b);
      }
      out.push_back(std::move(c));
    }
  }
  return out;
}

std::map<AttributionPlan::Gap, std::size_t> AttributionPlan::splittable_gaps() const {
  std::map<Gap, std::size_t> count;
  for (const Change& c : changes()) {
    if (c.resolved) continue;
    const Gap g{c.from, c.to};
    if (count.count(g) || open_inside(g) > 0) ++count[g];
  }
  return count;
}

std::size_t AttributionPlan::open_inside(const Gap& g) const {
  std::size_t n = 0;
  for (std::size_t p = g.from + 1; p < g.to; ++p) n += open(p);
  return n;
}

std::optional<std::size_t> AttributionPlan::next() const {
  const std::vector<std::size_t> one = next_k(1);
  if (one.empty()) return std::nullopt;
  return one.front();
}

std::vector<std::size_t> AttributionPlan::next_k(std::size_t k) const {
  const std::map<Gap, std::size_t> count = splittable_gaps();
  std::map<Gap, std::size_t> builds, room;
  for (const auto& [gap, n] : count) room[gap] = open_inside(gap);
  // First one build in each gap, the gaps with the most changes first (ties: the wider, then the
  // earlier): a round splits as many unresolved changes as it can.
  std::vector<Gap> order;
  for (const auto& [gap, n] : count) order.push_back(gap);
  std::stable_sort(order.begin(), order.end(), [&](const Gap& x, const Gap& y) {
    if (count.at(x) != count.at(y)) return count.at(x) > count.at(y);
    return x.to - x.from > y.to - y.from;
  });
  std::size_t left = k;
  for (const Gap& g : order)
    if (left > 0) builds[g] = 1, --left;
  // Then each further build to the gap with the most rounds still ahead of it, log(width) /
  // log(builds + 1), so that no gap's search outlasts the others' (ties: as above).
  for (; left > 0; --left) {
    const Gap* best = nullptr;
    double best_depth = 0;
    for (const Gap& g : order) {
      const std::size_t j = builds[g];
      if (j == 0 || j >= room[g]) continue;
      const double depth = std::log(double(g.to - g.from)) / std::log(double(j + 1));
      if (!best || depth > best_depth) best = &g, best_depth = depth;
    }
    if (!best) break;
    ++builds[*best];
  }
  // Each gap's builds evenly spaced in it: the open position nearest each target, the lower first.
  std::set<std::size_t> chosen;
  for (const auto& [gap, j] : builds) {
    const std::size_t w = gap.to - gap.from;
    for (std::size_t i = 1; i <= j; ++i) {
      const std::size_t target = gap.from + w * i / (j + 1);
      const auto free = [&](std::size_t p) {
        return p > gap.from && p < gap.to && open(p) && !chosen.count(p);
      };
      for (std::size_t d = 0; d < w; ++d) {
        if (target >= d && free(target - d)) {
          chosen.insert(target - d);
          break;
        }
        if (free(target + d)) {
          chosen.insert(target + d);
          break;
        }
      }
    }
  }
  return {chosen.begin(), chosen.end()};
}

bool AttributionPlan::needed(std::size_t position) const {
  for (const auto& [gap, n] : splittable_gaps())
    if (gap.from < position && position < gap.to) return true;
  return false;
}

std::size_t AttributionPlan::unresolved() const {
  std::size_t n = 0;
  for (const auto& [gap, count] : splittable_gaps()) n += count;
  return n;
}

std::size_t AttributionPlan::rounds_to_go(std::size_t k) const {
  const std::map<Gap, std::size_t> gaps = splittable_gaps();
  if (gaps.empty() || k == 0) return 0;
  // The deepest gap with its even share of the builds; and all the gaps' binary searches, k
  // builds a round (more gaps than builds are served in turn).
  const std::size_t share = std::max<std::size_t>(1, k / gaps.size());
  std::size_t deepest = 0, halvings = 0;
  for (const auto& [gap, n] : gaps) {
    std::size_t rounds = 0, halves = 0;
    for (std::size_t span = gap.to - gap.from; span > 1; span = (span + share) / (share + 1)) ++rounds;
    for (std::size_t span = gap.to - gap.from; span > 1; span = (span + 1) / 2) ++halves;
    deepest = std::max(deepest, rounds);
    halvings += halves;
  }
  return std::max(deepest, (halvings + k - 1) / k);
}

}  // namespace ra::triage
