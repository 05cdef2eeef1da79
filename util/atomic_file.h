// Files that are either complete or absent: write to a temporary file unique to this writer
// (PATH.<pid>.<n>.tmp, created exclusively), flush, fsync, then rename. A killed process, a full
// disk or a second writer never leaves half a file, or another writer's file, under the final name.
#pragma once

#include <string>

namespace ra::util {

// Writes `content` to `path` atomically; throws std::runtime_error naming the path and the system
// error (e.g. "No space left on device", with the free space) on failure, removing the temporary.
void write_file_atomic(const std::string& path, const std::string& content);

// A fresh, exclusively created, empty temporary file beside `path`, unique to this process and
// call: "PATH.<pid>.<n>.tmp". Throws like write_file_atomic.
std::string create_unique_temp(const std::string& path);

// Renames a finished temporary file into place after fsyncing it; throws like write_file_atomic.
void commit_file(const std::string& tmp_path, const std::string& path);

std::string read_file(const std::string& path);  // throws std::runtime_error when unreadable

// " (N bytes free on the file system of PATH)", or "" when it cannot be told: for disk-full errors.
std::string free_space_note(const std::string& path);

// The message of an I/O failure on `path`: "WHAT PATH: strerror(errno)", plus the free space when
// errno says the disk is full.
std::string io_error_message(const std::string& what, const std::string& path);

// Keeps the file at `path` beside it as evidence, never over a copy kept earlier: as PATH.damaged,
// or PATH.damaged.2, PATH.damaged.3, ..., the first of these names that no file holds. `move`:
// the file leaves `path` (renamed); otherwise it is copied. Returns the name it was kept under;
// throws std::runtime_error naming both files when it cannot be kept.
std::string keep_damaged_copy(const std::string& path, bool move);

}  // namespace ra::util
