// Error messages for values read from a TOML file: "file:line:column: message", naming the key and
// the allowed range, thrown as UserError. Shared by every reader of experiment files (runner/,
// scenes/, the studies) so that they all report bad input the same way.
#pragma once

#include <toml++/toml.h>

#include <cstdint>
#include <functional>
#include <set>
#include <string>
#include <vector>

namespace ra::util {

constexpr size_t kMaxRunNameLength = 100;  // characters of an experiment's `name`

class TomlLocator {
 public:
  explicit TomlLocator(std::string path) : path_(std::move(path)) {}
  const std::string& path() const { return path_; }

  // At the node's position (or the file start when it has no source).
  [[noreturn]] void fail(const toml::node* node, const std::string& message) const;
  [[noreturn]] void fail_at(toml::source_position at, const std::string& message) const;
  // Every key of `table` must be in `allowed`: a typo is an error, never silently ignored.
  // `where` prefixes the key in the message (e.g. "views.").
  void reject_unknown_keys(const toml::table& table, const std::string& where,
                           const std::set<std::string>& allowed) const;

  // The whole text of the file at `path`; UserError "PATH: cannot read WHAT (the system's
  // reason)", WHAT naming what the file was to be.
  static std::string read_text(const std::string& path,
                               const std::string& what = "the experiment file");
  // The TOML text of this file; a syntax error becomes "file:line:column: description".
  toml::table parse(const std::string& text) const;
  // An experiment's name: the top-level `name` when present (a non-empty string of letters,
  // digits, '_', '.', '-': it names output folders), otherwise the file's stem.
  std::string experiment_name(const toml::table& root) const;

  // An integer or floating-point value, as a double.
  double number(const toml::node& node, const std::string& key) const;
  // An integer in [lo, hi].
  int64_t integer(const toml::node& node, const std::string& key, int64_t lo, int64_t hi) const;
  // A finite number accepted by `ok`; else "'key' must be a number (allowed: ALLOWED)" or
  // "'key' = V is out of range (allowed: ALLOWED)".
  double number(const toml::node& node, const std::string& key, const std::string& allowed,
                const std::function<bool(double)>& ok) const;
  // An array of `lo` to `hi` elements; else "'key' must be WHAT".
  const toml::array& array(const toml::node& node, const std::string& key, size_t lo, size_t hi,
                           const std::string& what) const;
  // true or false; else "'key' must be true or false".
  bool boolean(const toml::node& node, const std::string& key) const;
  // A string; one of `allowed` when that is not empty ("'key' = \"V\" is out of range (allowed:
  // a, b)"), else any string (WHAT names it in the error: "a file name").
  std::string string(const toml::node& node, const std::string& key,
                     const std::vector<std::string>& allowed,
                     const std::string& what = "a string") const;

 private:
  std::string path_;
};

}  // namespace ra::util
