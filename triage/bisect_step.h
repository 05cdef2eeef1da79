// One step of a bisection: a commit of the Mesa tree described (subject, date, VERSION), built
// (builds/source_build.h, the tree already locked and left at the commit) and made to draw the
// primitives under judgement on the platform, through the audit's re-rendering of a run with the
// step's build added to the run's experiment (bisect_step_experiment).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "triage/bisect_types.h"

namespace ra::triage {

// The first 12 hex digits of a commit, as the progress lines name it.
std::string short_hash(const std::string& commit);

// `s.commit`'s date (ISO), subject and VERSION file, read with git in `source`.
void describe_commit(const std::string& source, BisectStep& s);

// What the builds of `o`'s platform drew of `primitives` with the build in `build_dir`: pixel
// hash and count by label, and the first batch's error.
Drawing draw_selection(const BisectOptions& o, const std::vector<BisectPrimitive>& primitives,
                       const std::string& build_dir);

// Builds `s.commit` and draws `primitives` with it, filling the step's build, times, drawing and
// error (a build or drawing that fails is the step's error, not an exception). Says the build's
// progress through `say`. Stops with util::Interrupted when the user interrupts.
void build_and_draw_step(const BisectOptions& o, const std::vector<BisectPrimitive>& primitives,
                         BisectStep& s, const std::function<void(const std::string&)>& say);

// Draws `primitives` with the step's build (s.build_dir), filling its drawing, draw time and error.
void draw_built_step(const BisectOptions& o, const std::vector<BisectPrimitive>& primitives,
                     BisectStep& s);

}  // namespace ra::triage
