// Attributing every changed primitive to its commit at once, with the builds shared.
//
// The commits between the good and the bad ref are a line (`git rev-list --first-parent`, perhaps
// restricted to paths): position 0 is the good ref, position n the bad ref. A built position has a
// pixel hash for each primitive it drew. For one primitive, two of its built positions with none
// of its own between them and different hashes hold a change: when they are neighbours on the line
// the later one is the commit that made it; otherwise the gap is unresolved. The next position to
// build is the middle of the gap holding the most unresolved changes (ties: the wider gap, then
// the earlier one), so one build halves the range of every primitive that changed there, and a
// bisection with one culprit takes the steps of a binary search.
//
// A primitive changed twice (good -> state 2 -> bad) shows three states and two changes, each
// found in turn. A position whose build or drawing failed is skipped for every primitive; a gap
// whose inner positions all failed ends unresolved with candidates (those positions and the gap's
// end). A change undone later in the range (A -> B -> A) is seen only where a built position
// falls inside it: the ends of the range cannot show it.
//
// K builds at once (`bisect --ways K`, next_k): first one build in each gap, the gaps with the
// most unresolved changes first (ties as next(): the wider, then the earlier), so that a round
// splits as many unresolved changes as it can; each further build goes to the gap with the most
// rounds still ahead of it, log(width) / log(builds + 1), so that a gap of few changes is not
// left to the last rounds; each gap's builds then stand evenly spaced in it. One culprit in n
// commits thus takes about log_(K+1) n rounds, and next_k(1) is next().
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace ra::triage {

class AttributionPlan {
 public:
  // Positions 0 (the good ref) to `last` (the bad ref).
  explicit AttributionPlan(std::size_t last);

  // What the build at `position` drew: pixel hash by primitive label. A primitive missing from
  // `hashes` is unknown there.
  void observe(std::size_t position, const std::map<std::string, uint64_t>& hashes);
  // The build or drawing at `position` failed: no primitive is known there.
  void fail(std::size_t position);
  // `label` is no longer attributed: forgotten at every position (a drawing time the steps could
  // not place).
  void forget(const std::string& label);

  // The next position to build; none when every change is attributed or only failed positions
  // are left inside the unresolved gaps.
  std::optional<std::size_t> next() const;
  // Up to `k` positions to build at once (fewer when fewer are open inside unresolved gaps),
  // in increasing order; empty when next() is none.
  std::vector<std::size_t> next_k(std::size_t k) const;
  // Whether a build at `position` would still split an unresolved change (a build of a round
  // whose range another result of the round already resolved is not needed).
  bool needed(std::size_t position) const;
  // Unresolved changes whose gap still holds an open position.
  std::size_t unresolved() const;
  // About how many rounds of `k` builds are left: the deepest gap's search, its share of the k
  // builds spread evenly over the gaps.
  std::size_t rounds_to_go(std::size_t k) const;

  struct Change {
    std::string label;
    std::size_t from = 0, to = 0;        // built positions with the two states
    uint64_t hash_before = 0, hash_after = 0;
    bool resolved = false;               // to == from + 1: position `to` made it
    std::vector<std::size_t> candidates;  // unresolved: the failed inner positions and `to`
  };
  // Every change seen so far, by label then position.
  std::vector<Change> changes() const;

  std::size_t last() const { return last_; }
  bool built(std::size_t position) const { return observed_.count(position) > 0; }

 private:
  struct Gap {
    std::size_t from, to;
    bool operator<(const Gap& o) const { return from != o.from ? from < o.from : to < o.to; }
  };
  // Unresolved changes by gap, for the gaps that hold an open position.
  std::map<Gap, std::size_t> splittable_gaps() const;
  std::size_t open_inside(const Gap& g) const;
  // Positions of `label`'s known states, in order.
  std::vector<std::size_t> known_positions(const std::string& label) const;
  bool open(std::size_t position) const;  // neither built nor failed

  std::size_t last_;
  std::map<std::size_t, std::map<std::string, uint64_t>> observed_;
  std::set<std::size_t> failed_;
  std::set<std::string> labels_;
};

}  // namespace ra::triage
