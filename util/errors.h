// The error channels (docs/operations.md, exit codes): bad input stops the command with a located message
// (UserError); a driver failure in one case is recorded in that case's record and the run goes on.
#pragma once

#include <stdexcept>
#include <string>

namespace ra::util {

// Bad input from a person: an experiment file, a command-line value, a data file. The message is
// complete ("file:line:column: what is wrong (allowed: ...)") and is printed as is.
class UserError : public std::runtime_error {
 public:
  explicit UserError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace ra::util
