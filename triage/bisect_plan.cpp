// The shared-build attribution of changed primitives (see the header).
#include "triage/bisect_plan.h"

#include <algorithm>

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

std::optional<std::size_t> AttributionPlan::next() const {
  // Unresolved changes by gap; a gap with no open position inside cannot be split.
  std::map<Gap, std::size_t> count;
  for (const Change& c : changes()) {
    if (c.resolved) continue;
    bool splittable = false;
    for (std::size_t p = c.from + 1; p < c.to && !splittable; ++p) splittable = open(p);
    if (splittable) ++count[Gap{c.from, c.to}];
  }
  const Gap* best = nullptr;
  std::size_t best_count = 0;
  for (const auto& [gap, n] : count) {  // in gap order: the earlier wins a full tie
    const bool wider = best && gap.to - gap.from > best->to - best->from;
    if (!best || n > best_count || (n == best_count && wider)) best = &gap, best_count = n;
  }
  if (!best) return std::nullopt;
  // The open position nearest the middle (the lower one first).
  const std::size_t mid = best->from + (best->to - best->from) / 2;
  for (std::size_t d = 0; d < best->to - best->from; ++d) {
    if (mid >= d && mid - d > best->from && open(mid - d)) return mid - d;
    if (mid + d < best->to && mid + d > best->from && open(mid + d)) return mid + d;
  }
  return std::nullopt;
}

}  // namespace ra::triage
