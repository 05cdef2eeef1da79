// The whole rendering-time study from an experiment file: scenes and paths built once, each
// platform measured in its own child process (timing_study.h), analysed, and written to the
// output folder (timing_outputs.h) with its study.json. Called by `renderaudit timing` and by
// `renderaudit run` for a file with a [timing] table.
#pragma once

#include "rundir/study_dir.h"

namespace ra::timing {

// Throws UserError for bad input (file:line:column) or a --platform not in the file. A platform
// whose measurement failed is named in the summary and sets findings.
rundir::StudyRunResult run_timing_study(const rundir::StudyRunOptions& options,
                                        bool figures = true);

}  // namespace ra::timing
