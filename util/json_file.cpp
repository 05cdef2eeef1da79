#include "util/json_file.h"

#include "util/atomic_file.h"

namespace ra::util {

nlohmann::json read_json_or_null(const std::string& path) {
  try {
    return nlohmann::json::parse(read_file(path));
  } catch (const std::exception&) {
    return nullptr;
  }
}

}  // namespace ra::util
