// The terrain LOD study's document (`renderaudit analyze`): DIR/lod_table.csv (per lambda and tau,
// lod_table.h) and DIR/lod.md, the study's text with its check and speed tables, from the
// frames.csv and lod_summary.json its run wrote (lod_run.h); study.json gets document "lod.md".
#pragma once

#include <string>

namespace ra::lod {

// Throws UserError when `dir` is not a complete LOD run.
void analyze_lod_study(const std::string& dir);

}  // namespace ra::lod
