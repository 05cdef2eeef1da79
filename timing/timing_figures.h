// The figures of the rendering-time study (plots/figure.h), drawn as it runs into DIR/figures/
// (timing_outputs.h): density of the system task's frame times per platform (the paper's Figure 3),
// and per platform, scene and method the measured and predicted frame times along the path.
#pragma once

#include <vector>

#include "plots/figure.h"
#include "timing/timing_outputs.h"

namespace ra::timing {

std::vector<plots::Figure> timing_figures(const StudyResults& r);

}  // namespace ra::timing
