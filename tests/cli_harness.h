// Helpers for end-to-end tests of the `renderaudit` program: run it, read what it wrote.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

namespace ra::testing_cli {

struct Outcome {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// Standard output of a shell command ("" when it cannot be started).
inline std::string shell_output(const std::string& cmd) {
  std::string out;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return out;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  ::pclose(p);
  return out;
}

// Collapses runs of white space (line breaks included) to one space: text from pdftotext wraps.
inline std::string squeeze(const std::string& s) {
  std::string out;
  for (char c : s) {
    const bool space = c == ' ' || c == '\n' || c == '\t' || c == '\r' || c == '\f';
    if (space) {
      if (!out.empty() && out.back() != ' ') out += ' ';
    } else {
      out += c;
    }
  }
  return out;
}

// The message of the exception of type E that `f` throws ("" when it throws none).
template <typename E, typename F>
std::string error_message(F f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

// Runs a shell command line and returns its exit code and output (stderr included).
inline Outcome run_command(const std::string& command_line) {
  Outcome o;
  const std::string cmd = command_line + " 2>&1";
  FILE* p = ::popen(cmd.c_str(), "r");
  std::array<char, 4096> buf;
  size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0) o.output.append(buf.data(), n);
  const int status = ::pclose(p);
  o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return o;
}

// Runs `renderaudit ARGS` (a shell fragment) and returns its exit code and output.
inline Outcome run_renderaudit(const std::string& args) {
  return run_command(std::string(RA_BINARY) + " " + args);
}

// A new empty directory for one test. The process id keeps tests that ctest runs at once (each
// in its own process) out of each other's way, even when they share a helper that names a dir.
inline std::string fresh_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("renderaudit_test_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

inline void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

// Every record line of a run directory, with the timing columns (the last two) removed, as a set
// ordered by content: equal sets mean identical records whatever the sharding.
inline std::multiset<std::string> records_without_timing(const std::string& run_dir) {
  std::multiset<std::string> rows;
  for (const auto& e : std::filesystem::directory_iterator(run_dir + "/records")) {
    if (e.path().extension() != ".csv") continue;
    std::ifstream in(e.path());
    std::string line;
    std::getline(in, line);  // header
    // The last two columns, render_us and batch_size, depend on timing and on how the
    // primitives fell into batches.
    while (std::getline(in, line)) {
      line.erase(line.rfind(','));
      rows.insert(line.substr(0, line.rfind(',')));
    }
  }
  return rows;
}

}  // namespace ra::testing_cli
