// Measuring in a child process. Mesa picks its GL driver (GALLIUM_DRIVER) when a process makes
// its first context, once: a study that measures a platform therefore draws in a forked child, and
// the child's result crosses back to the parent as JSON through a scratch file.
//
// run_in_child flushes stdout and stderr, forks, and runs `work` in the child. The child writes
// `work`'s JSON (or the message of the exception it threw) to SCRATCH_DIR/.NAME.json atomically
// and leaves with _exit (exit status 0, 3 when `work` threw, 4 when the file could not be
// written): nothing of the parent's (atexit handlers, static destructors, test frameworks) runs
// in it. The parent waits for the child, reads the file and removes it, whatever happened.
//
// The parent process should not have made a GL context of its own before: a child inherits the
// driver its parent chose.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

namespace ra::util {

// The child gave no result. what(): the message of the exception `work` threw, as it was; or,
// when the child left without a result (a crash, an _exit of its own),
// "the measuring process died of signal N" /
// "the measuring process exited with status N without a result (why the file is unreadable)".
class ChildProcessError : public std::runtime_error {
 public:
  ChildProcessError(const std::string& what, bool user_error)
      : std::runtime_error(what), user_error_(user_error) {}
  // `work` threw a ra::util::UserError (bad input rather than a failure of the driver).
  bool user_error() const { return user_error_; }

 private:
  bool user_error_;
};

// Runs `work` in a forked child and returns its JSON. `name` names the scratch file
// (SCRATCH_DIR/.NAME.json, which must be writable) and the child's own complaints on stderr.
// Throws ChildProcessError when the child gave no result, std::runtime_error when fork fails.
nlohmann::json run_in_child(const std::string& scratch_dir, const std::string& name,
                            const std::function<nlohmann::json()>& work);

}  // namespace ra::util
