// Files that are either complete or absent: write to `path.tmp`, flush, fsync, then rename.
// A killed process or a full disk never leaves half a file under the final name.
#pragma once

#include <string>

namespace ra {

// Writes `content` to `path` atomically; throws std::runtime_error naming the path and the system
// error (e.g. "No space left on device") on failure, removing the temporary file.
void write_file_atomic(const std::string& path, const std::string& content);

// Renames a finished temporary file into place after fsyncing it; throws like write_file_atomic.
void commit_file(const std::string& tmp_path, const std::string& path);

std::string read_file(const std::string& path);  // throws std::runtime_error when unreadable

}  // namespace ra
