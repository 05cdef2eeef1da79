#include "util/toml_locator.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

#include "util/errors.h"
#include "util/nearest_name.h"

namespace ra::util {

void TomlLocator::fail(const toml::node* node, const std::string& message) const {
  fail_at(node ? node->source().begin : toml::source_position{}, message);
}

void TomlLocator::fail_at(toml::source_position at, const std::string& message) const {
  std::ostringstream out;
  out << path_ << ":";
  if (at.line > 0)
    out << at.line << ":" << at.column;
  else
    out << "1:1";
  out << ": " << message;
  throw UserError(out.str());
}

void TomlLocator::reject_unknown_keys(const toml::table& table, const std::string& where,
                                      const std::set<std::string>& allowed) const {
  const std::vector<std::string> names(allowed.begin(), allowed.end());
  for (const auto& [key, node] : table) {
    if (allowed.count(std::string(key.str()))) continue;
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
    const std::string near = nearest_name(std::string(key.str()), names);
    fail_at(key.source().begin, "unknown key '" + where + std::string(key.str()) + "'" +
                                    (near.empty() ? "" : "; did you mean '" + near + "'?") +
                                    " (allowed: " + list + ")");
  }
}

toml::table TomlLocator::parse(const std::string& text) const {
  try {
    return toml::parse(text, path_);
  } catch (const toml::parse_error& e) {
    fail_at(e.source().begin, std::string(e.description()));
  }
}

std::string TomlLocator::read_text(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UserError(path + ": cannot read " + what + " (" + std::strerror(errno) + ")");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A run's name becomes a directory (outputs/NAME): a plain file name, never a path, ".", ".." or a
// hidden file, and short enough for any file system.
static bool valid_run_name(const std::string& name) {
  static const std::string allowed =
      "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_.-";
  return !name.empty() && name.size() <= kMaxRunNameLength && std::isalnum((unsigned char)name[0]) &&
         name.find_first_not_of(allowed) == std::string::npos;
}

std::string TomlLocator::experiment_name(const toml::table& root) const {
  static const std::string rule = "(allowed: 1 to " + std::to_string(kMaxRunNameLength) +
                                  " letters, digits, '_', '.', '-', starting with a letter or digit)";
  const toml::node* n = root.get("name");
  if (!n) {
    const std::string file = path_.substr(path_.find_last_of('/') + 1);
    const std::string stem = file.substr(0, file.rfind(".toml"));
    if (!valid_run_name(stem))
      fail(nullptr, "the file name '" + stem + "' cannot name the run's directory; set 'name' " + rule);
    return stem;
  }
  const auto* s = n->as_string();
  if (!s || !valid_run_name(s->get()))
    fail(n, "'name' must be a plain file name " + rule + ", not " +
                (s ? "'" + s->get() + "'" : std::string("a value of another type")));
  return s->get();
}

double TomlLocator::number(const toml::node& node, const std::string& key) const {
  if (auto v = node.as_integer()) return double(v->get());
  if (auto v = node.as_floating_point()) return v->get();
  fail(&node, "'" + key + "' must be a number");
}

int64_t TomlLocator::integer(const toml::node& node, const std::string& key, int64_t lo,
                             int64_t hi) const {
  auto v = node.as_integer();
  if (!v)
    fail(&node, "'" + key + "' must be an integer (allowed: " + std::to_string(lo) + " to " +
                    std::to_string(hi) + ")");
  if (v->get() < lo || v->get() > hi)
    fail(&node, "'" + key + "' = " + std::to_string(v->get()) + " is out of range (allowed: " +
                    std::to_string(lo) + " to " + std::to_string(hi) + ")");
  return v->get();
}

double TomlLocator::number(const toml::node& node, const std::string& key,
                           const std::string& allowed,
                           const std::function<bool(double)>& ok) const {
  double v = 0;
  if (const auto* i = node.as_integer())
    v = double(i->get());
  else if (const auto* f = node.as_floating_point())
    v = f->get();
  else
    fail(&node, "'" + key + "' must be a number (allowed: " + allowed + ")");
  if (!std::isfinite(v) || !ok(v)) {
    std::ostringstream s;  // six significant digits: the value as a person wrote it, mostly
    s << "'" << key << "' = " << v << " is out of range (allowed: " << allowed << ")";
    fail(&node, s.str());
  }
  return v;
}

const toml::array& TomlLocator::array(const toml::node& node, const std::string& key, size_t lo,
                                      size_t hi, const std::string& what) const {
  const auto* a = node.as_array();
  if (!a || a->size() < lo || a->size() > hi) fail(&node, "'" + key + "' must be " + what);
  return *a;
}

bool TomlLocator::boolean(const toml::node& node, const std::string& key) const {
  const auto* b = node.as_boolean();
  if (!b) fail(&node, "'" + key + "' must be true or false");
  return b->get();
}

std::string TomlLocator::string(const toml::node& node, const std::string& key,
                                const std::vector<std::string>& allowed,
                                const std::string& what) const {
  std::string list;
  for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
  const auto* s = node.as_string();
  if (!s)
    fail(&node, "'" + key + "' must be a string (allowed: " + (list.empty() ? what : list) + ")");
  if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), s->get()) == allowed.end())
    fail(&node, "'" + key + "' = \"" + s->get() + "\" is out of range (allowed: " + list + ")");
  return s->get();
}

}  // namespace ra::util
