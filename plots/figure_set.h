// Draws a study's figures into DIR/figures/ (STEM.png, STEM.pdf, STEM.csv per figure) and writes
// DIR/figures/index.json, the index `renderaudit report` reads (plots/plot_run.h's schema), in
// drawing order. Each figure is drawn under a temporary name and renamed, so that it is either
// complete or absent; the index is written last. Starts a private Xvfb when DISPLAY is unset.
#pragma once

#include <string>
#include <vector>

#include "plots/figure.h"

namespace ra::plots {

// Returns the paths written. Throws UserError when DIR/figures cannot be created.
std::vector<std::string> write_figure_set(const std::vector<Figure>& figures, const std::string& dir);

}  // namespace ra::plots
