// Helpers for end-to-end tests of the `renderaudit` program: run it, read what it wrote.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "metrics/records.h"
#include "rundir/records_format.h"
#include "rundir/shard_file.h"
#include "util/zstd_stream.h"
#include "util/child_process.h"

namespace ra::testing_cli {

struct Outcome {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// Splits a command line into words as a shell would for plain words, 'single' and "double" quoted
// ones, and nothing else: no variables, globs, pipes or redirections. No shell ever runs (a path
// with a ';' in it is a path); a test needing more builds its ChildSpec itself.
inline std::vector<std::string> split_words(const std::string& line) {
  std::vector<std::string> words;
  std::string word;
  bool in_word = false;
  char quote = 0;
  for (char c : line) {
    if (quote) {
      if (c == quote) quote = 0; else word += c;
    } else if (c == '\'' || c == '"') {
      quote = c;
      in_word = true;
    } else if (c == ' ' || c == '\t' || c == '\n') {
      if (in_word) words.push_back(word), word.clear(), in_word = false;
    } else {
      word += c;
      in_word = true;
    }
  }
  if (in_word) words.push_back(word);
  return words;
}

// Output (stdout and stderr) of a command line split by split_words ("" when it cannot start).
inline std::string shell_output(const std::string& cmd) {
  ra::util::ChildSpec spec;
  spec.argv = split_words(cmd);
  spec.stdin_null = true;
  try {
    return ra::util::run_program(spec).output;
  } catch (const std::exception&) {
    return "";
  }
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

// Runs a command line (split_words) and returns its exit code and output (stderr included).
inline Outcome run_command(const std::string& command_line) {
  ra::util::ChildSpec spec;
  spec.argv = split_words(command_line);
  spec.stdin_null = true;
  const ra::util::ProgramResult r = ra::util::run_program(spec);
  return Outcome{r.exit_code(), r.output};
}

// Runs `renderaudit ARGS` (words as split_words reads them) and returns its exit code and output.
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

// The text of a records file, decompressed when it is a .csv.zst one.
inline std::string read_records_text(const std::string& path) {
  if (ra::util::has_zstd_extension(path)) return ra::util::read_zstd_file(path);
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Replaces a records file's text, compressed (as one zstd frame) when it is a .csv.zst one.
inline void write_records_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!ra::util::has_zstd_extension(path)) {
    out << text;
    return;
  }
  ra::util::ZstdFrameWriter z(out);
  z.write(text);
  z.end_frame();
}

// Seals a records file again after a test edited it (rundir/shard_file.h), as if a run had written
// those records: drops its old trailer, appends the one its content now has.
inline void reseal_records_file(const std::string& path) {
  const std::string text = read_records_text(path);
  std::string body;
  std::size_t rows = 0, start = 0;
  for (bool header = true; start < text.size(); header = false) {
    std::size_t end = text.find('\n', start);
    end = end == std::string::npos ? text.size() : end + 1;
    if (text[start] != '#') {
      body.append(text, start, end - start);
      rows += !header;
    }
    start = end;
  }
  write_records_text(path, body + ra::rundir::shard_trailer(body, rows));
}

// Every record line of a run directory, with the timing columns removed, as a set ordered by
// content: equal sets mean identical records whatever the sharding.
inline std::multiset<std::string> records_without_timing(const std::string& run_dir) {
  // render_us, batch_size, host_us and clock depend on timing and on how the primitives fell
  // into batches.
  using C = metrics::RecordColumn;
  const std::set<std::size_t> timing = {std::size_t(C::kRenderUs), std::size_t(C::kBatchSize),
                                        std::size_t(C::kHostUs), std::size_t(C::kClock)};
  std::multiset<std::string> rows;
  for (const auto& e : std::filesystem::directory_iterator(run_dir + "/records")) {
    if (!ra::rundir::is_records_file_name(e.path().filename().string())) continue;
    std::istringstream in(read_records_text(e.path().string()));
    std::string line;
    std::getline(in, line);  // header
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#') continue;  // the shard file's seal
      std::string kept;
      std::size_t begin = 0;
      for (std::size_t k = 0;; ++k) {
        const std::size_t comma = line.find(',', begin);
        if (!timing.count(k))
          kept += line.substr(begin, comma == std::string::npos ? comma : comma - begin) + ",";
        if (comma == std::string::npos) break;
        begin = comma + 1;
      }
      rows.insert(kept);
    }
  }
  return rows;
}

}  // namespace ra::testing_cli
