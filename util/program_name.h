// How a command printed for a user to paste names this program: "renderaudit" when that name on
// PATH is this very program (installed by `make install`, or a folder on PATH), else the absolute
// path of the running executable (e.g. /home/me/renderaudit/build/renderaudit), which pastes from
// any folder (quoted for the shell where it needs to be). A process that is not renderaudit
// itself (a test or benchmark program linking the libraries) says "renderaudit".
#pragma once

#include <string>

namespace ra::util {

std::string program_for_commands();

}  // namespace ra::util
