// Durations as a clock or in words (see the header).
#include "util/duration_text.h"

#include <cmath>
#include <cstdio>

namespace ra::util {
namespace {

struct ClockParts {
  long hours, minutes, seconds;  // minutes and seconds below 60
};

// `seconds` (finite, not negative) rounded to whole seconds and split.
ClockParts clock_parts(double seconds) {
  const long t = std::lround(seconds);
  return {t / 3600, (t / 60) % 60, t % 60};
}

bool unknown_duration(double seconds) { return !std::isfinite(seconds) || seconds < 0; }

}  // namespace

std::string duration_text(double seconds, const char* unknown) {
  if (unknown_duration(seconds)) return unknown;
  const ClockParts c = clock_parts(seconds);
  char buf[48];
  std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", c.hours, c.minutes, c.seconds);
  return buf;
}

std::string elapsed_text(double seconds) {
  if (unknown_duration(seconds)) return "?";
  char buf[48];
  if (seconds < 9.95) {  // tenths while they still say something
    std::snprintf(buf, sizeof buf, "%.1f s", seconds);
    return buf;
  }
  const ClockParts c = clock_parts(seconds);
  if (c.hours > 0)
    std::snprintf(buf, sizeof buf, "%ld h %02ld min", c.hours, c.minutes);
  else if (c.minutes > 0)
    std::snprintf(buf, sizeof buf, "%ld min %ld s", c.minutes, c.seconds);
  else
    std::snprintf(buf, sizeof buf, "%ld s", c.seconds);
  return buf;
}

}  // namespace ra::util
