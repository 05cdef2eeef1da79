// Judging a bisection's drawings: which primitives the two ends draw differently (the others say
// nothing about the change), how a step's pixels compare with the ends', and, once the plan
// (bisect_plan.h) has placed every change between two neighbouring commits, the culprit commits
// and what stays unattributed. Pure but for the culprits' descriptions, read with git.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "triage/bisect_types.h"
#include "triage/bisect_plan.h"

namespace ra::triage {

// The selection split by the two ends' drawings: `judged` the primitives they draw differently,
// in selection order; `dropped` the labels of those they draw alike.
void split_by_ends(const std::vector<BisectPrimitive>& selection, const Drawing& good,
                   const Drawing& bad, std::vector<BisectPrimitive>& judged,
                   std::vector<std::string>& dropped);

// The pixel hashes of `d` for the judged primitives it drew.
std::map<std::string, uint64_t> judged_hashes(const std::vector<BisectPrimitive>& judged,
                                              const Drawing& d);

// A step's drawing against the two ends, in words: "N like the good ref, M like the bad ref, K
// like neither".
std::string drawing_summary(const std::vector<BisectPrimitive>& judged, const Drawing& good,
                            const Drawing& bad, const Drawing& d);

// The plan's changes as `r.culprits` (one per commit, its primitives in selection order, their
// pixel counts before and after, each commit described with git in `source`) and
// `r.unattributed`; `line` maps positions to commits. Says each culprit through `say`.
void collect_culprits(const AttributionPlan& plan, const std::vector<std::string>& line,
                      const std::vector<BisectPrimitive>& judged, const std::string& source,
                      BisectResult& r, const std::function<void(const std::string&)>& say);

}  // namespace ra::triage
