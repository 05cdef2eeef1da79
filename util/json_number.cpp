// Numbers of JSON documents, written and read as text (json_number.h).
#include "util/json_number.h"

#include <cmath>

#include "util/number_text.h"

namespace ra::util {

nlohmann::json finite_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json();
}

std::string json_number_text(const nlohmann::json& v, const char* format) {
  return v.is_number() ? format_double(format, v.get<double>()) : "n/a";
}

}  // namespace ra::util
