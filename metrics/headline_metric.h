// Each kind's headline error: the one metric that stands for a primitive's accuracy where a
// single number is quoted (an audit's changed primitives, the speed tables' error columns, a run's
// summary). PE for points, LSEu for lines, TEu for triangles, in pixels: the records' columns pe,
// lse_u, te_u (records.h); and the same divided by the window: pe_norm, lse_u_norm, te_u_norm.
#pragma once

#include "geometry/primitive.h"
#include "metrics/records.h"

namespace ra::metrics {

// The records column of `kind`'s headline error: "pe", "lse_u", "te_u".
const char* headline_column(geometry::Kind kind);

// `r`'s headline error as a record of `kind` (kNA where it does not apply).
double headline_value(const Record& r, geometry::Kind kind);

// The records column of `kind`'s headline error divided by the window (records.h: / sqrt(W*H)
// for points and lines, / (W*H) for triangles): "pe_norm", "lse_u_norm", "te_u_norm".
const char* headline_norm_column(geometry::Kind kind);

// `r`'s headline error so divided (kNA where it does not apply).
double headline_norm_value(const Record& r, geometry::Kind kind);

// The form a run's summary (summary.md, analysis/run_summary.h) quotes: PE in pixels for points,
// the headline error divided by the window for lines and triangles. Its label in the summary's
// table ("PE (px)", "LSEu-norm", "TEu-norm") and `r`'s value (kNA where it does not apply).
const char* summary_metric_label(geometry::Kind kind);
double summary_metric_value(const Record& r, geometry::Kind kind);

}  // namespace ra::metrics
