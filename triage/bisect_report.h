// OUT/bisect.md: a bisection written for the driver's developers, ready to paste into their issue
// tracker: what is wrong in one sentence, the GL rule broken, the versions and commits affected and
// not, the first bad commit with the files it changed, the standalone C reproducer inline with its
// build and run lines for both sides of the change, pictures of the worst primitive drawn by the
// commit and by its parent, every selected primitive's pixels on both sides, the steps of the
// bisection and the command that repeats it.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "triage/bisect.h"

namespace ra::triage {

void write_bisect_report(const BisectOptions& options, const BisectResult& result,
                         const std::vector<BisectPrimitive>& judged,
                         const std::function<void(const std::string&)>& say);

// What a conformance rule name means, in one clause ("a line drawn as nothing where GL requires
// fragments inside the window"); the name itself when unknown.
std::string rule_meaning(const std::string& rule);

}  // namespace ra::triage
