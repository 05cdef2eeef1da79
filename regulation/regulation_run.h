// The decision-theoretic regulation study (Horvitz & Lengyel, "Perception, Attention, and
// Resources: A Decision-Theoretic Approach to Graphics Rendering", UAI 1997): levels of
// detail from meshoptimizer's simplifier (lod_chain.h), H4 costs from the rendering-time study
// (cost_model.h), perceptual cost and attention (attention.h, equations 3-7), the greedy policy
// with the best-single-item check against the exact optimum and baselines (policies.h), random
// instances (random_instances.h), and the plans rendered along a camera path (plan_rendering.h).
//
// Outputs in DIR (all written atomically; study.json last):
//   instances.csv     one row per random instance: values and losses of every policy, ratios
//   lod_levels.csv    one row per object and level: triangles, vertices, #tv, error (m)
//   budget_sweep.csv  one row per frame x budget x policy: expected perceptual cost, predicted time
//   frames.csv        the same rows with the measured frame times (every repetition) and skips
//   pixels.csv        measured #pix only: per planned frame, visible object and level the pixel
//                     query's count, with the bounding-sphere estimate
//   regulation.json   settings, summaries and the numbers behind the figures
//   study.json        kind "regulation" (rundir/study_dir.h)
// `analyze` adds regulation.md (and rewrites study.json; regulation_document.h), `plot`
// DIR/figures/ (regulation_figures.h).
#pragma once

#include "rundir/study_dir.h"

namespace ra::regulation {

// Computes and measures; writes study.json last (analysed = false, document empty). findings:
// a check failed (a greedy / optimal value ratio above 2, the DP differing from brute force, a
// plan over budget, or the rendering process failing); the summary says which.
rundir::StudyRunResult run_regulation_study(const rundir::StudyRunOptions& options);

}  // namespace ra::regulation
