// The terrain level-of-detail study (Lindstrom & Pascucci 2001): `renderaudit run / analyze / report` of an
// experiment file with a top-level [lod] table (lod_experiment.h).
//
// run: builds the height field and its nested hierarchy, flies the camera path, and for every
// frame and tau refines the LOD (the experiment's lambda, drawn and timed, and each check_lambda,
// only refined and checked), checks conformity, seams and the measured screen error, draws the
// LOD and the full-resolution mesh `repetitions` times each and compares their images. Writes
//   DIR/frames.csv        one row per (lambda, tau, frame) (columns in lod_table.h)
//   DIR/lod_summary.json  settings, terrain, renderer, lambdas, the checks' verdicts
//   DIR/study.json        last (kind "lod", analysed false)
// analyze (lod_document.h): DIR/lod_table.csv (per lambda and tau), DIR/lod.md, study.json
// (document "lod.md"). plot (lod_figures.h): DIR/figures/.
#pragma once

#include "rundir/study_dir.h"

namespace ra::lod {

// Measures; findings = true when a check of the experiment's own lambda failed on some frame
// (a mesh not conforming, a seam used differently from its two sides, or a measured screen error
// above tau). Throws UserError for a bad experiment or height file.
rundir::StudyRunResult run_lod_study(const rundir::StudyRunOptions& options);

}  // namespace ra::lod
