// The study's tables as Markdown (DIR/timing.md), read back by `renderaudit report DIR`: the
// platforms and their timers, the system task and c, the scenes (the paper's Table 5), the fitted
// heuristics, Table 6 and the CPU-vs-GPU timer comparison. Built from timing.json alone, so a
// report can be remade from the file. Times in the tables: ms for frames, us for coefficients'
// units as stated, ms^2 for Table 6.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace ra::timing {

std::string timing_markdown(const nlohmann::json& timing_json);

}  // namespace ra::timing
