#include "util/json_file.h"

#include "util/atomic_file.h"
#include "util/errors.h"

namespace ra::util {

nlohmann::json parse_json_document(const std::string& text, const std::string& path) {
  int depth = 0;
  bool in_string = false, escaped = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        throw UserError(path + ": arrays and objects nested deeper than " +
                        std::to_string(kMaxJsonDepth) + " levels (at byte " + std::to_string(i) +
                        "); not a document this program writes");
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return nlohmann::json::parse(text);
}

nlohmann::json read_json_or_null(const std::string& path) {
  try {
    return parse_json_document(read_file(path), path);
  } catch (const std::exception&) {
    return nullptr;
  }
}

}  // namespace ra::util
