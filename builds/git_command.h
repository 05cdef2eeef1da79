// Running git in a tree: the one helper the bisection, the nightly watch and the source builds
// ask (an argument list, no shell; the output with its trailing white space trimmed).
#pragma once

#include <string>
#include <vector>

namespace ra::builds {

struct GitResult {
  bool ok = false;  // git exited 0
  std::string out;  // stdout and stderr, trailing white space trimmed
};

// git -C DIR ARGS... (detached-HEAD advice off).
GitResult git(const std::string& dir, std::vector<std::string> args);

}  // namespace ra::builds
