// One writer per directory: an advisory lock (flock) on DIR/.lock, held for as long as the object
// lives and released by the kernel when the process dies, however it dies. The file also records
// who holds it (pid, host, start time), so a refused writer can say who is writing.
#pragma once

#include <string>

namespace ra::util {

class DirLock {
 public:
  // Takes the lock on `dir` (which must exist) for `what` ("run", "audit", ...), or throws
  // UserError "DIR is being written by process P (run) on host H since T; ADVICE" when another
  // process holds it. The descriptor is close-on-exec: started programs never inherit the lock.
  DirLock(const std::string& dir, const std::string& what,
          const std::string& advice = "wait for it to finish, or choose another --out");
  ~DirLock();
  DirLock(const DirLock&) = delete;
  DirLock& operator=(const DirLock&) = delete;

  static std::string lock_path(const std::string& dir);  // DIR/.lock

  // Who holds the lock of `dir` now ("process P (run) on host H since T"), or "" when nobody
  // does (no lock file, or its writer is gone). Takes nothing.
  static std::string current_holder(const std::string& dir);

 private:
  int fd_ = -1;
};

}  // namespace ra::util
