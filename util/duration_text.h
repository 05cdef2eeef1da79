// Durations written for people, in the two spellings the project uses: a clock ("1:02:03") where
// the text is rewritten in place or stands in a column (progress lines, status, bisection
// tables), and words ("2 min 41 s") where it ends a sentence (a run's summary). Both stand on
// one rounding to whole seconds. (The shell scripts and the Makefile spell their own whole
// seconds as elapsed_text does, from `date +%s`, without the program.)
#pragma once

#include <string>

namespace ra::util {

// Seconds as "H:MM:SS" ("0:00:07", "1:02:03"); `unknown` ("--:--") when not finite or negative
// (a time left that cannot be told yet).
std::string duration_text(double seconds, const char* unknown = "--:--");

// Wall time as a person reads it in a summary line: "0.4 s", "13 s", "2 min 41 s", "1 h 05 min";
// "?" when not finite or negative.
std::string elapsed_text(double seconds);

}  // namespace ra::util
