// OUT/bisect.md: a bisection written for the driver's developers, ready to paste into their issue
// tracker: the culprit commits in one table (what each changed, by kind, view group and GL
// verdict), then one section per culprit: what changed in one sentence, the GL rule broken or
// "allowed by GL", the files it changed, the standalone C reproducer of its worst primitive with
// the lines that run it on the commit and on the one before, pictures of both, and its primitives'
// pixels; what stays unattributed and why; the steps of the bisection and the command that
// repeats it.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "triage/bisect_types.h"

namespace ra::triage {

void write_bisect_report(const BisectOptions& options, const BisectResult& result,
                         const std::vector<BisectPrimitive>& judged,
                         const std::function<void(const std::string&)>& say);

// What a conformance rule name means, in one clause ("a line drawn as nothing where GL requires
// fragments inside the window"); the name itself when unknown.
std::string rule_meaning(const std::string& rule);

}  // namespace ra::triage
