// The counts of what changed (see the header).
#include "audit/change_counts.h"

#include <map>
#include <tuple>

namespace ra::audit {
namespace {

bool allowed_by_gl(metrics::Conformance c) {
  return c == metrics::Conformance::kExact || c == metrics::Conformance::kSnapped ||
         c == metrics::Conformance::kWithinSpec;
}

}  // namespace

ChangeCategory change_category(const ChangedPrimitive& c) {
  using metrics::Conformance, metrics::Visibility;
  if (c.before.visibility == Visibility::kTrueVisible &&
      c.after.visibility == Visibility::kFalseInvisible)
    return ChangeCategory::kNotDrawn;
  if (new_violation(c)) return ChangeCategory::kNewViolation;
  if (c.before.conformance == Conformance::kViolation &&
      c.after.conformance != Conformance::kViolation)
    return ChangeCategory::kFixed;
  if (allowed_by_gl(c.before.conformance) && allowed_by_gl(c.after.conformance))
    return ChangeCategory::kAllowed;
  return ChangeCategory::kOther;
}

std::vector<ChangeCounts> count_changes(const PrimitiveComparison& comparison) {
  using Key = std::tuple<std::size_t, int, int>;  // pair, kind, view group
  std::map<Key, ChangeCounts> by_key;
  const auto counts_of = [&](std::size_t pair, geometry::Kind kind, int group) -> ChangeCounts& {
    ChangeCounts& c = by_key[{pair, int(kind), group}];
    c.pair = pair, c.kind = kind, c.view_group = group;
    return c;
  };
  for (const ViewCounts& v : comparison.views)
    if (v.compared > 0) counts_of(v.pair, v.kind, v.view_group).compared += v.compared;
  for (const ChangedPrimitive& p : comparison.changed) {
    if (p.recheck == Recheck::kFlake) continue;
    ChangeCounts& c = counts_of(p.pair, p.kind, p.view_group);
    const ChangeCategory category = change_category(p);
    const bool broken = new_violation(p);
    ++c.changed;
    c.not_drawn += category == ChangeCategory::kNotDrawn;
    c.newly_drawn += p.before.visibility == metrics::Visibility::kFalseInvisible &&
                     p.after.visibility == metrics::Visibility::kTrueVisible;
    c.new_violations += broken;
    c.not_drawn_violations += category == ChangeCategory::kNotDrawn && broken;
    c.fixed_violations += category == ChangeCategory::kFixed;
    c.allowed += category == ChangeCategory::kAllowed;
  }
  std::vector<ChangeCounts> out;
  for (auto& [key, c] : by_key) out.push_back(c);
  return out;
}

}  // namespace ra::audit
