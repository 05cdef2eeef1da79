// The inputs of `renderaudit bisect` (triage/bisect.h) checked: everything that can be refused is
// refused before anything is built.
#pragma once

#include <string>

#include "triage/bisect_types.h"

namespace ra::triage {

// What the check found: the tree's git folder and the commits of the two refs.
struct CheckedInputs {
  std::string git_dir, good, bad;
};

// Checks the run, the tree (a clean git checkout), the refs (commits, the good one an ancestor of
// the bad one), OUT (a folder outside the tree, created) and the platform, and makes the
// selection. Completes `o` (the tree's canonical path, the default OUT and platform) and fills the
// selection of `result`. Throws UserError saying what is wrong and how to mend it.
CheckedInputs check_bisect_inputs(BisectOptions& o, BisectResult& result);

}  // namespace ra::triage
