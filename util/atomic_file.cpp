#include "util/atomic_file.h"

#include <fcntl.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace ra::util {

std::string free_space_note(const std::string& path) {
  std::string dir = std::filesystem::path(path).parent_path().string();
  if (dir.empty()) dir = ".";
  struct statvfs st {};
  if (::statvfs(dir.c_str(), &st) != 0) return "";
  const unsigned long long bytes = static_cast<unsigned long long>(st.f_bavail) * st.f_frsize;
  return " (" + std::to_string(bytes) + " bytes free on the file system of " + dir + ")";
}

std::string io_error_message(const std::string& what, const std::string& path) {
  const int err = errno;
  std::string msg = what + " " + path + ": " + std::strerror(err);
  if (err == ENOSPC || err == EDQUOT) msg += free_space_note(path);
  return msg;
}

static std::runtime_error io_error(const std::string& what, const std::string& path) {
  return std::runtime_error(io_error_message(what, path));
}

static void fsync_path(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) throw io_error("cannot open", path);
  const int rc = ::fsync(fd);
  const int saved = errno;
  ::close(fd);
  errno = saved;
  if (rc != 0) throw io_error("cannot sync", path);
}

std::string create_unique_temp(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  for (int tries = 0; tries < 100; ++tries) {
    const std::string tmp = path + "." + std::to_string(::getpid()) + "." +
                            std::to_string(counter++) + ".tmp";
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd >= 0) {
      ::close(fd);
      return tmp;
    }
    if (errno != EEXIST) throw io_error("cannot create", tmp);
  }
  throw std::runtime_error("cannot create a unique temporary file beside " + path);
}

void commit_file(const std::string& tmp_path, const std::string& path) {
  try {
    fsync_path(tmp_path);
    if (std::rename(tmp_path.c_str(), path.c_str()) != 0) throw io_error("cannot rename to", path);
  } catch (...) {
    std::remove(tmp_path.c_str());
    throw;
  }
}

void write_file_atomic(const std::string& path, const std::string& content) {
  const std::string tmp = create_unique_temp(path);
  FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw io_error("cannot create", tmp);
  const bool ok = std::fwrite(content.data(), 1, content.size(), f) == content.size();
  const int saved = errno;
  if (std::fclose(f) != 0 || !ok) {
    if (!ok) errno = saved;
    const std::runtime_error e = io_error("cannot write", path);
    std::remove(tmp.c_str());
    throw e;
  }
  commit_file(tmp, path);
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::stringstream buf;
  buf << in.rdbuf();
  return buf.str();
}

std::string keep_damaged_copy(const std::string& path, bool move) {
  for (int n = 1; n <= 100000; ++n) {
    const std::string kept = path + ".damaged" + (n > 1 ? "." + std::to_string(n) : "");
    std::error_code ec;
    if (move) {
      // a hard link fails on an existing name (no copy is ever replaced); then the name goes
      if (::link(path.c_str(), kept.c_str()) == 0) {
        if (::unlink(path.c_str()) != 0)
          throw std::runtime_error(io_error_message("kept as " + kept + ", but cannot remove", path));
        return kept;
      }
      if (errno == EEXIST) continue;
      if (std::filesystem::exists(kept, ec)) continue;  // a file system without hard links
      std::filesystem::rename(path, kept, ec);
    } else {
      if (std::filesystem::exists(kept, ec)) continue;
      std::filesystem::copy_file(path, kept, std::filesystem::copy_options::none, ec);
      if (ec == std::errc::file_exists) continue;
    }
    if (ec)
      throw std::runtime_error("cannot keep " + path + " as " + kept + ": " + ec.message() +
                               free_space_note(kept));
    return kept;
  }
  throw std::runtime_error("cannot keep " + path + ": every name " + path +
                           ".damaged.N up to 100000 is taken");
}

}  // namespace ra::util
