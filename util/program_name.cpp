// The program's name in printed commands (see the header).
#include "util/program_name.h"

#include <filesystem>

#include "util/path_search.h"
#include "util/shell_quote.h"

namespace fs = std::filesystem;

namespace ra::util {
namespace {

std::string find_name() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec || exe.filename() != "renderaudit") return "renderaudit";
  for (const std::string& dir : path_folders()) {  // not the current folder: no name that pastes
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
