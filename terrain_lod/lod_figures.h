// The terrain LOD study's figures (`renderaudit plot`) in DIR/figures/: speed against image error,
// triangles and measured screen error against tau, from analyze's lod_table.csv (lod_table.h).
#pragma once

#include <string>

namespace ra::lod {

// Needs analyze_lod_study's lod_table.csv; throws UserError when it is missing.
void plot_lod_study(const std::string& dir);

}  // namespace ra::lod
