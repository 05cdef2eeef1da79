// Sealing JSON state files (see the header).
#include "util/json_seal.h"

#include "util/fnv1a.h"

namespace ra::util {

std::string json_seal(const nlohmann::json& doc) {
  nlohmann::json copy = doc;
  if (copy.is_object()) copy.erase("seal");
  Fnv1a64 h;
  h.add(copy.dump());
  return hex64(h.value);
}

nlohmann::json sealed(nlohmann::json doc) {
  doc["seal"] = json_seal(doc);
  return doc;
}

std::string seal_problem(const nlohmann::json& doc) {
  if (!doc.is_object() || !doc.contains("seal")) return "'seal' is missing";
  if (!doc["seal"].is_string()) return "'seal' must be a string of 16 hex digits";
  if (doc["seal"].get<std::string>() != json_seal(doc))
    return "'seal' does not match the content: the file was changed or damaged after it was "
           "written";
  return "";
}

}  // namespace ra::util
