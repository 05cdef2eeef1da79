// The regulation study's document (`renderaudit analyze`): DIR/regulation.md from the
// DIR/regulation.json its run wrote (regulation_run.h), and the reading of that file the figures
// share.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace ra::regulation {

// DIR/regulation.md from DIR/regulation.json; study.json rewritten with document = "regulation.md",
// analysed = true. Throws UserError when DIR is not a complete regulation run.
void analyze_regulation_study(const std::string& dir);

// DIR/regulation.json of a complete regulation run. Throws UserError when DIR is not one (no
// study.json of kind regulation) or the file cannot be read.
nlohmann::json read_regulation_json(const std::string& dir);

}  // namespace ra::regulation
