// Programs found on $PATH (path_search.h).
#include "util/path_search.h"

#include <unistd.h>

#include <cstdlib>
#include <sstream>

namespace ra::util {

std::vector<std::string> path_folders() {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "/usr/local/bin:/usr/bin:/bin");
  std::vector<std::string> folders;
  for (std::string dir; std::getline(dirs, dir, ':');)
    if (!dir.empty()) folders.push_back(dir);
  return folders;
}

std::string find_on_path(const std::string& program) {
  for (const std::string& dir : path_folders()) {
    const std::string candidate = dir + "/" + program;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return "";
}

}  // namespace ra::util
