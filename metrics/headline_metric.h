// Each kind's headline error: the one metric that stands for a primitive's accuracy where a
// single number is quoted (an audit's changed primitives, the speed tables' error columns). PE
// for points, LSEu for lines, TEu for triangles, in pixels: the records' columns pe, lse_u, te_u
// (records.h).
#pragma once

#include "geometry/primitive.h"
#include "metrics/records.h"

namespace ra::metrics {

// The records column of `kind`'s headline error: "pe", "lse_u", "te_u".
const char* headline_column(geometry::Kind kind);

// `r`'s headline error as a record of `kind` (kNA where it does not apply).
double headline_value(const Record& r, geometry::Kind kind);

}  // namespace ra::metrics
