// The program's name in printed commands (see the header).
#include "util/program_name.h"

#include <cstdlib>
#include <filesystem>
#include <sstream>

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
  // quoted for the shell when the path holds anything but letters, digits and / . _ - +
  const std::string p = exe.string();
  if (p.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789/._-+") ==
      std::string::npos)
    return p;
  std::string quoted = "'";
  for (char c : p) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace

std::string program_for_commands() {
  static const std::string name = find_name();
  return name;
}

}  // namespace ra::util
