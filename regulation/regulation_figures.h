// The regulation study's figures (`renderaudit plot`): the ratio histogram of the random
// instances, expected perceptual cost against the budget, and (when rendered) frame skips and
// measured against predicted frame time, from DIR/regulation.json (regulation_document.h).
#pragma once

#include <string>

namespace ra::regulation {

// The figures through plots::write_figure_set into DIR/figures/. Throws UserError when DIR is not
// a complete regulation run or has not been analysed.
void plot_regulation_study(const std::string& dir);

}  // namespace ra::regulation
