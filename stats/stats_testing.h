// Test support for the statistics tests (included by analysis/*_test.cpp only): readers for the
// NIST reference data in tests/data/strd, the log relative error, deterministic samples, and a
// runner that asks SciPy (Debian's python3-scipy, /usr/bin/python3) for independent values.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "util/child_process.h"

namespace ra::stats::testing {

inline std::string strd_path(const std::string& file) {
  return std::string(RA_SOURCE_DIR) + "/tests/data/strd/" + file;
}

inline std::vector<std::string> read_lines(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

// Whitespace-separated numbers of a line; empty when any token is not a number.
inline std::vector<double> numbers_of(const std::string& line) {
  std::istringstream in(line);
  std::vector<double> out;
  std::string token;
  while (in >> token) {
    char* end = nullptr;
    const double v = std::strtod(token.c_str(), &end);
    if (end != token.c_str() + token.size()) return {};
    out.push_back(v);
  }
  return out;
}

// The number after `key` on the first line that starts with `line_start` and contains `key`.
inline double certified_after(const std::vector<std::string>& lines, const std::string& line_start,
                              const std::string& key) {
  for (const auto& l : lines) {
    if (l.rfind(line_start, 0) != 0) continue;
    const auto at = l.find(key);
    if (at != std::string::npos) return std::strtod(l.c_str() + at + key.size(), nullptr);
  }
  throw std::runtime_error("no certified value '" + line_start + "..." + key + "'");
}

// Rows of numbers after the last line that starts with "Data:" (the StRD files; the certified
// values and the data do not sit on the same lines in every file: NUMACC* have them on lines 41-42
// with data from line 61, Lew on 31-32 / 41, Michelso on 22-23 / 32).
inline std::vector<std::vector<double>> strd_data_rows(const std::vector<std::string>& lines) {
  std::size_t start = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].rfind("Data:", 0) == 0) start = i + 1;
  }
  std::vector<std::vector<double>> rows;
  for (std::size_t i = start; i < lines.size(); ++i) {
    auto row = numbers_of(lines[i]);
    if (!row.empty()) rows.push_back(std::move(row));
  }
  return rows;
}

// NIST StRD univariate summary statistics data set.
struct StrdUnivariate {
  std::vector<double> data;
  double mean = 0;
  double sd = 0;
};

inline StrdUnivariate read_strd_univariate(const std::string& file) {
  const auto lines = read_lines(strd_path(file));
  StrdUnivariate s;
  s.mean = certified_after(lines, "Sample Mean", "ybar:");
  s.sd = certified_after(lines, "Sample Standard Deviation", "s:");
  for (const auto& row : strd_data_rows(lines)) s.data.push_back(row.at(0));
  const double n = certified_after(lines, "Number of Observations:", ":");
  if (static_cast<double>(s.data.size()) != n) throw std::runtime_error(file + ": wrong count");
  return s;
}

// NIST StRD one-way ANOVA data set: groups (in treatment order) and the certified table.
struct StrdAnova {
  std::vector<std::vector<double>> groups;
  double df_between = 0, ss_between = 0, ms_between = 0, f = 0;
  double df_within = 0, ss_within = 0, ms_within = 0;
  double r_squared = 0, residual_sd = 0;
};

inline StrdAnova read_strd_anova(const std::string& file) {
  const auto lines = read_lines(strd_path(file));
  StrdAnova a;
  for (const auto& l : lines) {
    if (l.rfind("Between ", 0) == 0 || l.rfind("Within ", 0) == 0) {
      // "Between Treatment   8 1.68E+00 2.1E-01 2.1E+01": the numbers follow the two words
      std::istringstream in(l);
      std::string w1, w2;
      in >> w1 >> w2;
      std::string rest;
      std::getline(in, rest);
      const auto v = numbers_of(rest);
      if (w1 == "Between") {
        a.df_between = v.at(0), a.ss_between = v.at(1), a.ms_between = v.at(2), a.f = v.at(3);
      } else {
        a.df_within = v.at(0), a.ss_within = v.at(1), a.ms_within = v.at(2);
      }
    }
  }
  a.r_squared = certified_after(lines, "", "Certified R-Squared");
  a.residual_sd = certified_after(lines, "", "Standard Deviation");
  for (const auto& row : strd_data_rows(lines)) {
    const auto g = static_cast<std::size_t>(row.at(0));
    if (a.groups.size() < g) a.groups.resize(g);
    a.groups[g - 1].push_back(row.at(1));
  }
  return a;
}

// Rows of an e-Handbook / Dataplot data file: the numeric rows after the first dashed line.
inline std::vector<std::vector<double>> read_dataplot_rows(const std::string& file) {
  const auto lines = read_lines(strd_path(file));
  std::vector<std::vector<double>> rows;
  bool in_data = false;
  for (const auto& l : lines) {
    if (!in_data) {
      in_data = l.rfind("---", 0) == 0;
      continue;
    }
    auto row = numbers_of(l);
    if (!row.empty()) rows.push_back(std::move(row));
  }
  return rows;
}

// Log relative error, -log10(|x - c| / |c|) (McCullough 1998): the number of correct significant
// digits. +infinity when x == c exactly; -log10|x| when c == 0 (log absolute error).
inline double lre(double computed, double certified) {
  if (computed == certified) return std::numeric_limits<double>::infinity();
  if (certified == 0) return -std::log10(std::fabs(computed));
  return -std::log10(std::fabs(computed - certified) / std::fabs(certified));
}

// Relative difference |a - b| / max(|a|, |b|), 0 when both are 0.
inline double relative_difference(double a, double b) {
  const double scale = std::max(std::fabs(a), std::fabs(b));
  return scale == 0 ? 0 : std::fabs(a - b) / scale;
}

// splitmix64: a small fixed generator, so every run of the tests sees the same samples.
class Generator {
 public:
  explicit Generator(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  // uniform on (0, 1), never 0 or 1
  double uniform() { return (static_cast<double>(next() >> 11) + 0.5) * 0x1.0p-53; }
  // standard normal (Box-Muller; one of the pair)
  double normal() {
    const double u1 = uniform();
    const double u2 = uniform();
    return std::sqrt(-2 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }

 private:
  std::uint64_t state_;
};

inline std::vector<double> normal_sample(std::size_t n, double mean, double sd,
                                         std::uint64_t seed) {
  Generator g(seed);
  std::vector<double> v(n);
  for (auto& x : v) x = mean + sd * g.normal();
  return v;
}

inline std::vector<double> lognormal_sample(std::size_t n, double mu, double sigma,
                                            std::uint64_t seed) {
  Generator g(seed);
  std::vector<double> v(n);
  for (auto& x : v) x = std::exp(mu + sigma * g.normal());
  return v;
}

inline std::vector<double> exponential_sample(std::size_t n, double scale, std::uint64_t seed) {
  Generator g(seed);
  std::vector<double> v(n);
  for (auto& x : v) x = -scale * std::log(g.uniform());
  return v;
}

// Normal noise rounded to multiples of 2^-10, so that offset + noise is exact for offsets up to
// 2^42 (4e12): statistics of the offset data must equal those of the noise.
inline std::vector<double> dyadic_noise(std::size_t n, double sd, std::uint64_t seed) {
  auto v = normal_sample(n, 0, sd, seed);
  for (auto& x : v) x = std::round(x * 1024) / 1024;
  return v;
}

inline std::vector<double> plus(std::vector<double> v, double offset) {
  for (auto& x : v) x += offset;
  return v;
}

// A fresh, empty temporary directory for one test.
inline std::filesystem::path temp_dir(const std::string& tag) {
  static std::atomic<int> counter{0};
  const auto dir =
      std::filesystem::temp_directory_path() /
      ("ra_stats_" + tag + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Runs `body` (Python) under /usr/bin/python3 with numpy, scipy and scipy.stats imported, the JSON
// `input` bound to `inp`; the script must bind its result to `out` (JSON-serialisable, no NaN).
// Throws (the test fails) when SciPy is missing, naming scripts/install-deps.sh, or the script
// fails. SciPy is the independent reference: missing it is a broken test setup, not a skip.
inline nlohmann::json run_scipy(const std::string& body, const nlohmann::json& input) {
  const char* python = "/usr/bin/python3";
  if (!std::filesystem::exists(python)) {
    throw std::runtime_error(
        "/usr/bin/python3 is missing; the statistics tests need it with SciPy: run "
        "scripts/install-deps.sh (Debian package python3-scipy)");
  }
  const auto dir = temp_dir("scipy");
  const auto script = dir / "reference.py";
  const auto in_path = dir / "input.json";
  const auto out_path = dir / "output.json";
  const auto err_path = dir / "stderr.txt";
  {
    std::ofstream s(script);
    s << "import json, math, sys\n"
         "try:\n"
         "    import numpy as np\n"
         "    import scipy, scipy.special, scipy.stats\n"
         "except ImportError as e:\n"
         "    sys.stderr.write(str(e))\n"
         "    sys.exit(3)\n"
         "inp = json.load(open(sys.argv[1]))\n"
      << body << "\njson.dump(out, open(sys.argv[2], 'w'), allow_nan=False)\n";
    std::ofstream i(in_path);
    i << input.dump();
  }
  util::ChildSpec spec;  // an argument list: no shell between us and the script
  spec.argv = {python, script.string(), in_path.string(), out_path.string()};
  spec.stderr_path = err_path.string();
  spec.stdin_null = true;
  const int status = util::wait_child(util::start_child(spec).pid);
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream err_in(err_path);
  const std::string err((std::istreambuf_iterator<char>(err_in)), std::istreambuf_iterator<char>());
  if (code == 3) {
    throw std::runtime_error("SciPy is not installed for /usr/bin/python3 (" + err +
                             "): run scripts/install-deps.sh (Debian package python3-scipy)");
  }
  if (code != 0) {
    throw std::runtime_error("the SciPy reference script failed (exit " + std::to_string(code) +
                             "), script kept in " + dir.string() + ":\n" + err);
  }
  std::ifstream out_in(out_path);
  nlohmann::json out = nlohmann::json::parse(out_in);
  std::filesystem::remove_all(dir);
  return out;
}

}  // namespace ra::stats::testing
