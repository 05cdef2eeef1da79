// The program's name in printed commands (see the header).
#include "util/program_name.h"

#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "util/shell_quote.h"

namespace fs = std::filesystem;

namespace ra::util {
namespace {

std::string find_name() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec || exe.filename() != "renderaudit") return "renderaudit";
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    if (dir.empty()) continue;  // the current folder: not a name that pastes elsewhere
    const fs::path candidate = fs::path(dir) / "renderaudit";
    if (fs::exists(candidate, ec) && fs::equivalent(candidate, exe, ec)) return "renderaudit";
    if (fs::exists(candidate, ec)) break;  // another renderaudit comes first on PATH
  }
  return shell_quote(exe.string());
}

}  // namespace

std::string program_for_commands() {
  static const std::string name = find_name();
  return name;
}

}  // namespace ra::util
