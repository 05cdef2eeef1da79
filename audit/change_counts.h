// What changed between the two sides of an audit, counted per pair, kind and view group: the
// numbers of the driver upgrade report (report/upgrade_sentences.h says them in words). They are
// counted from the audit's own comparison (audit/audit_compare.h), so a primitive is changed here
// exactly when the audit calls it changed: its status, visibility, lit pixels or GL verdict
// differ, it took no worker down on either side, and its difference did not disappear on
// re-render (a flake).
//
// Each changed primitive falls in one category, the first that holds:
//   not drawn      true-visible before, false-invisible after
//   new violation  after a GL violation, before none (metrics/conformance.h)
//   fixed          before a violation, after none
//   allowed        before and after drawn as GL allows (exact, snapped or within-spec)
//   other          the rest (rules not judged, or broken on both sides)
// A primitive not drawn is most often also a new violation: `not_drawn_violations` counts those
// that are both, so that a reader can nest the two counts.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "audit/audit_compare.h"

namespace ra::audit {

// The categories, most severe first (the order the upgrade report shows them in).
enum class ChangeCategory { kNotDrawn, kNewViolation, kFixed, kOther, kAllowed };

// The category of a changed primitive (the first rule above that holds).
ChangeCategory change_category(const ChangedPrimitive& c);

// The counts of one pair, kind and view group. Every count is a number of primitives.
struct ChangeCounts {
  std::size_t pair = 0;  // index into the audit's PlatformPair list
  geometry::Kind kind = geometry::Kind::kPoint;
  int view_group = 0;                  // 0 = A
  uint64_t compared = 0;               // a record on both sides
  uint64_t changed = 0;                // changed as the audit counts them (flakes excluded)
  uint64_t not_drawn = 0;              // true-visible -> false-invisible
  uint64_t newly_drawn = 0;            // false-invisible -> true-visible
  uint64_t new_violations = 0;         // after a violation, before none (audit's new_violation)
  uint64_t fixed_violations = 0;       // category fixed
  uint64_t allowed = 0;                // category allowed
  uint64_t not_drawn_violations = 0;   // not drawn and a new violation
};

// The counts of every pair, kind and view group that compared a primitive, ordered by pair, kind
// and view group. Primitives marked Recheck::kFlake are left out, as the audit leaves them out.
std::vector<ChangeCounts> count_changes(const PrimitiveComparison& comparison);

}  // namespace ra::audit
