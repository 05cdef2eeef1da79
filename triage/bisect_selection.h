// Which primitives a bisection draws: the run's changed primitives between two platforms, all of
// them, or, when there are more than the cap, a sample that covers every stratum (kind, view group
// and conformance transition): the strata in turn, each giving its largest pixel change first.
#pragma once

#include <string>
#include <vector>

#include "triage/bisect_types.h"

namespace ra::triage {

struct Selection {
  std::vector<BisectPrimitive> primitives;
  std::size_t changed = 0;  // changed primitives the run holds, after the --kind/--view filters
  std::string rule;         // how they were chosen, in words
};

// The selection of `o` (explicit primitives, or the run's changes). Throws UserError when a
// platform is not in the run, or nothing changed.
Selection select_primitives(const BisectOptions& o);

// "KIND:VIEW:INDEX" -> primitive; throws UserError naming the allowed form.
BisectPrimitive parse_primitive(const std::string& text);

}  // namespace ra::triage
