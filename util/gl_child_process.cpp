// Measuring in a child process (gl_child_process.h).
#include "util/gl_child_process.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "util/atomic_file.h"
#include "util/child_process.h"
#include "util/errors.h"

namespace ra::util {
namespace {

// The file's envelope: {"result": JSON} or {"error": message, "user_error": bool}.
[[noreturn]] void child_main(const std::string& file, const std::string& name,
                             const std::function<nlohmann::json()>& work) {
  int code = 0;
  nlohmann::json envelope;
  try {
    envelope = {{"result", work()}};
  } catch (const UserError& e) {
    envelope = {{"error", e.what()}, {"user_error", true}};
    code = 3;
  } catch (const std::exception& e) {
    envelope = {{"error", e.what()}, {"user_error", false}};
    code = 3;
  } catch (...) {
    envelope = {{"error", "an exception of unknown type"}, {"user_error", false}};
    code = 3;
  }
  try {
    write_file_atomic(file, envelope.dump());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "renderaudit %s: %s\n", name.c_str(), e.what());
    code = 4;
  }
  std::fflush(stdout);
  std::fflush(stderr);
  ::_exit(code);
}

}  // namespace

nlohmann::json run_in_child(const std::string& scratch_dir, const std::string& name,
                            const std::function<nlohmann::json()>& work) {
  const std::string file = scratch_dir + "/." + name + ".json";
  std::error_code ec;
  std::filesystem::remove(file, ec);
  std::fflush(stdout);
  std::fflush(stderr);
  pid_t pid = -1;
  try {
    pid = fork_child([&]() -> int { child_main(file, name, work); });
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(name + ": " + e.what());
  }
  const int status = wait_child(pid);
  nlohmann::json envelope;
  std::string unreadable;
  try {
    envelope = nlohmann::json::parse(read_file(file));
    if (!envelope.is_object() || (!envelope.contains("result") && !envelope.contains("error")))
      unreadable = file + " holds neither a result nor an error";
  } catch (const std::exception& e) {
    unreadable = e.what();
  }
  std::filesystem::remove(file, ec);
  // A child killed while writing leaves its temporary (atomic_file.h: FILE.<pid>.<n>.tmp).
  const std::string temp_prefix = "." + name + ".json." + std::to_string(pid) + ".";
  for (const auto& e : std::filesystem::directory_iterator(scratch_dir, ec))
    if (e.path().filename().string().rfind(temp_prefix, 0) == 0) std::filesystem::remove(e.path(), ec);
  if (unreadable.empty()) {
    if (envelope.contains("result")) return std::move(envelope["result"]);
    const nlohmann::json& message = envelope["error"];
    throw ChildProcessError(message.is_string() ? message.get<std::string>() : message.dump(),
                            envelope.value("user_error", false));
  }
  std::string error = "the measuring process ";
  if (WIFSIGNALED(status))
    error += "died of signal " + std::to_string(WTERMSIG(status));
  else
    error += "exited with status " + std::to_string(WEXITSTATUS(status)) + " without a result (" +
             unreadable + ")";
  throw ChildProcessError(error, false);
}

}  // namespace ra::util
