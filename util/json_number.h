// Numbers of the project's JSON documents (study results, audit files): a double written as null
// when it is not finite (JSON has no NaN), and a number read back as text for a person, "n/a" where
// the document holds null (number_text.h spells the number).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace ra::util {

// `v`, or null when it is NaN or infinite.
nlohmann::json finite_or_null(double v);

// A number of a JSON document through a printf format of one double ("%.4g", "%.2f"); "n/a" when
// `v` is not a number (null, absent).
std::string json_number_text(const nlohmann::json& v, const char* format = "%.4g");

}  // namespace ra::util
