// The name a person most likely meant when they mistyped one: "did you mean 'orientations'?"
// for a command, an option or an experiment-file key.
#pragma once

#include <string>
#include <vector>

namespace ra::util {

// The name of `names` nearest to `typed` (Levenshtein edit distance at most a third of its length,
// at least 2), or "" when none is that near.
std::string nearest_name(const std::string& typed, const std::vector<std::string>& names);

}  // namespace ra::util
