// Choosing meson options from a Mesa tree's own options file (see the header).
#include "builds/meson_plan.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "util/errors.h"

namespace ra::builds {
namespace {

// The quoted strings of `s` in order ('x' or "x").
std::vector<std::string> quoted_strings(const std::string& s) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '\'' && s[i] != '"') continue;
    const std::size_t end = s.find(s[i], i + 1);
    if (end == std::string::npos) break;
    out.push_back(s.substr(i + 1, end - i - 1));
    i = end;
  }
  return out;
}

// The text after `key :` up to the end of its value (a quoted string or a [list]).
std::string value_of(const std::string& body, const std::string& key) {
  for (std::size_t at = body.find(key); at != std::string::npos; at = body.find(key, at + 1)) {
    std::size_t i = at + key.size();
    if (at > 0 && (std::isalnum(static_cast<unsigned char>(body[at - 1])) || body[at - 1] == '_'))
      continue;
    while (i < body.size() && std::isspace(static_cast<unsigned char>(body[i]))) ++i;
    if (i >= body.size() || body[i] != ':') continue;
    ++i;
    while (i < body.size() && std::isspace(static_cast<unsigned char>(body[i]))) ++i;
    if (i < body.size() && body[i] == '[') {
      const std::size_t end = body.find(']', i);
      return body.substr(i, end == std::string::npos ? std::string::npos : end - i + 1);
    }
    std::size_t end = body.find_first_of(",\n", i);
    return body.substr(i, end == std::string::npos ? std::string::npos : end - i);
  }
  return "";
}

bool has(const std::vector<std::string>& v, const std::string& x) {
  return std::find(v.begin(), v.end(), x) != v.end();
}

// "12.0.0" -> {12, 0, 0}
std::vector<int> version_parts(const std::string& v) {
  std::vector<int> out;
  int cur = -1;
  for (char c : v) {
    if (std::isdigit(static_cast<unsigned char>(c))) {
      cur = (cur < 0 ? 0 : cur * 10) + (c - '0');
    } else if (cur >= 0) {
      out.push_back(cur);
      cur = -1;
      if (c != '.') break;
    }
  }
  if (cur >= 0) out.push_back(cur);
  return out;
}

}  // namespace

std::map<std::string, MesonOption> parse_meson_options(const std::string& text) {
  // Comments out first: a '#' outside quotes ends the line.
  std::string clean;
  clean.reserve(text.size());
  char quote = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quote) {
      if (c == quote) quote = 0;
      clean += c;
    } else if (c == '\'' || c == '"') {
      quote = c;
      clean += c;
    } else if (c == '#') {
      while (i < text.size() && text[i] != '\n') ++i;
      clean += '\n';
    } else {
      clean += c;
    }
  }
  std::map<std::string, MesonOption> out;
  for (std::size_t at = clean.find("option("); at != std::string::npos;
       at = clean.find("option(", at + 1)) {
    // The call's body: up to the parenthesis that closes it.
    int depth = 0;
    std::size_t end = at + 6;
    char q = 0;
    for (; end < clean.size(); ++end) {
      const char c = clean[end];
      if (q) {
        if (c == q) q = 0;
      } else if (c == '\'' || c == '"') {
        q = c;
      } else if (c == '(') {
        ++depth;
      } else if (c == ')' && --depth == 0) {
        break;
      }
    }
    const std::string body = clean.substr(at + 7, end - at - 7);
    const std::vector<std::string> strings = quoted_strings(body);
    if (strings.empty()) continue;
    MesonOption o;
    const std::vector<std::string> type = quoted_strings(value_of(body, "type"));
    if (!type.empty()) o.type = type.front();
    o.choices = quoted_strings(value_of(body, "choices"));
    out[strings.front()] = o;
  }
  return out;
}

bool glslang_builds_lavapipe(const std::string& glslang_version) {
  const std::vector<int> v = version_parts(glslang_version);
  if (v.empty()) return false;
  const int minor = v.size() > 1 ? v[1] : 0;
  return v[0] > 12 || (v[0] == 12 && minor >= 2);
}

std::string meson_string(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) {  // a line break would end the string (meson's \xhh escape)
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", u);
      out += hex;
      continue;
    }
    if (c == '\\' || c == '\'') out += '\\';
    out += c;
  }
  return out + "'";
}

std::string native_file_text(const std::string& llvm_config) {
  return "[binaries]\nllvm-config = " + meson_string(llvm_config) + "\ncmake = '/bin/false'\n";
}

void check_llvm_config(const std::string& path) {
  std::string shown;  // the path as it can be printed: control characters as \xHH
  bool control = false;
  for (unsigned char c : path) {
    if (c < 0x20 || c == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      shown += hex;
      control = true;
    } else {
      shown += char(c);
    }
  }
  const std::string named = "--llvm-config '" + shown + "'";
  if (path.empty()) throw util::UserError("builds build: --llvm-config is empty: name llvm-config");
  if (control)
    throw util::UserError("builds build: " + named +
                          " holds a control character (allowed: a path without control "
                          "characters, e.g. /usr/bin/llvm-config-15)");
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw util::UserError("builds build: " + named +
                          " is missing (llvm-15-dev; scripts/install-mesa-build-deps.sh)");
  if (!std::filesystem::is_regular_file(path, ec) || ::access(path.c_str(), X_OK) != 0)
    throw util::UserError("builds build: " + named +
                          " is not an executable file (allowed: llvm-config, e.g. "
                          "/usr/bin/llvm-config-15)");
}

MesonPlan plan_meson_build(const MesonPlanInputs& in) {
  MesonPlan p;
  const auto& o = in.options;
  const auto option = [&](const std::string& name) -> const MesonOption* {
    const auto it = o.find(name);
    return it == o.end() ? nullptr : &it->second;
  };
  // A feature option takes enabled/disabled; older trees spell some of them as booleans.
  const auto on = [&](const std::string& name, bool value) {
    const MesonOption* m = option(name);
    if (!m) return;
    std::string v;
    if (m->type == "boolean") {
      v = value ? "true" : "false";
    } else if (m->type == "combo" && !has(m->choices, "enabled")) {
      v = value ? "true" : "false";
    } else {
      v = value ? "enabled" : "disabled";
    }
    p.chosen.push_back("-D" + name + "=" + v);
  };
  if (const MesonOption* g = option("gallium-drivers")) {
    const bool split = has(g->choices, "llvmpipe") && has(g->choices, "softpipe");
    p.chosen.push_back(std::string("-Dgallium-drivers=") + (split ? "llvmpipe,softpipe" : "swrast"));
  }
  if (const MesonOption* v = option("vulkan-drivers")) {
    const bool lavapipe = has(v->choices, "swrast") && glslang_builds_lavapipe(in.glslang_version);
    p.chosen.push_back(std::string("-Dvulkan-drivers=") + (lavapipe ? "swrast" : ""));
    if (!lavapipe)
      p.notes.push_back("lavapipe not built: glslang " +
                        (in.glslang_version.empty() ? std::string("is not installed")
                                                    : in.glslang_version + " is older than 12.2") +
                        " (Debian 12 has 12.0); add -Dvulkan-drivers=swrast to try");
  }
  if (option("platforms")) p.chosen.push_back("-Dplatforms=");
  on("egl", true);
  on("gbm", false);
  if (const MesonOption* glx = option("glx")) {
    (void)glx;
    p.chosen.push_back("-Dglx=disabled");
  }
  on("glvnd", true);
  on("llvm", true);
  on("shared-llvm", true);
  on("osmesa", true);
  if (option("osmesa") == nullptr)
    p.notes.push_back("no OSMesa in this tree (removed in Mesa 25.1): draw with egl-*@BUILD");
  on("shared-glapi", true);
  on("gles1", false);
  on("valgrind", false);
  on("libunwind", false);
  on("lmsensors", false);
  on("zstd", true);
  p.setup = {"meson", "setup", in.build_dir, in.source_dir, "--native-file", in.native_file,
             "--prefix", in.prefix, "--libdir", "lib/x86_64-linux-gnu", "--buildtype", "release",
             "-Db_ndebug=true"};
  p.setup.insert(p.setup.end(), p.chosen.begin(), p.chosen.end());
  p.setup.insert(p.setup.end(), in.extra.begin(), in.extra.end());
  p.compile = {"ninja", "-C", in.build_dir};
  p.install = {"ninja", "-C", in.build_dir, "install"};
  return p;
}

}  // namespace ra::builds
