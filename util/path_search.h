// Programs found as a shell finds them: the folders of $PATH in order. Every lookup of a program
// by name (Xvfb, pdfunite, renderaudit itself) asks here.
#pragma once

#include <string>
#include <vector>

namespace ra::util {

// The folders of $PATH in order, empty entries (the current folder) left out;
// /usr/local/bin, /usr/bin, /bin when PATH is not set.
std::vector<std::string> path_folders();

// The first FOLDER/program of path_folders() that this process may execute, or ""
// (e.g. find_on_path("Xvfb")).
std::string find_on_path(const std::string& program);

}  // namespace ra::util
