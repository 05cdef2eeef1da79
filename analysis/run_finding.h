// What a run found, in the one line a terminal shows at the end of `renderaudit report` (and so of
// `make report`): the primitives that break a GL rasterization rule, counted by `analyze`
// (DIR/analysis/tally.json, run_tally.h), per platform and kind with the view groups they fall in,
// and the file that lists each with the command that draws it. The tables stay in their files.
//
//   finding: 2 violations (GL rules broken) in 64,000 primitives: osmesa-softpipe lines 2
//   (group B: 150 deg, 128x128); each in DIR/analysis/violations.md
//   finding: no violation (no GL rule broken) in 64,000 primitives; 93.4% drawn exactly as the
//   reference rasterizer
#pragma once

#include <string>

#include "analysis/run_tally.h"

namespace ra::analysis {

// The line, without a line break. `run_dir` names the violations file.
std::string run_finding_line(const RunTally& tally, const std::string& run_dir);

}  // namespace ra::analysis
