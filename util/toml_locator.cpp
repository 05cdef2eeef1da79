#include "util/toml_locator.h"

#include <fstream>
#include <sstream>

#include "util/errors.h"

namespace ra {

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
  for (const auto& [key, node] : table) {
    if (allowed.count(std::string(key.str()))) continue;
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
    fail_at(key.source().begin,
            "unknown key '" + where + std::string(key.str()) + "' (allowed: " + list + ")");
  }
}

toml::table TomlLocator::parse(const std::string& text) const {
  try {
    return toml::parse(text, path_);
  } catch (const toml::parse_error& e) {
    fail_at(e.source().begin, std::string(e.description()));
  }
}

std::string TomlLocator::read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UserError(path + ": cannot read the experiment file");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string TomlLocator::experiment_name(const toml::table& root) const {
  const toml::node* n = root.get("name");
  if (!n) {
    const std::string stem = path_.substr(path_.find_last_of('/') + 1);
    return stem.substr(0, stem.rfind(".toml"));
  }
  const auto* s = n->as_string();
  if (!s || s->get().empty() ||
      s->get().find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_.-") !=
          std::string::npos)
    fail(n, "'name' must be a non-empty string of letters, digits, '_', '.', '-'");
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

}  // namespace ra
