// Seconds as "H:MM:SS" for progress lines and status; "--:--" (or `unknown`) when not finite or
// negative (a time left that cannot be told yet).
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace ra::util {

inline std::string duration_text(double seconds, const char* unknown = "--:--") {
  if (!std::isfinite(seconds) || seconds < 0) return unknown;
  const long t = std::lround(seconds);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", t / 3600, (t / 60) % 60, t % 60);
  return buf;
}

}  // namespace ra::util
