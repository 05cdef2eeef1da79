// The meson command lines that build a Mesa source tree's software drivers (llvmpipe, softpipe;
// lavapipe where glslang allows) into an install prefix. Mesa's options change over its history
// (`gallium-drivers=swrast` became `llvmpipe,softpipe`, `glvnd` went from boolean to feature,
// `osmesa` and `shared-glapi` were removed), so the options are chosen from the tree's own
// meson_options.txt / meson.options: an option the tree lacks is never passed.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace ra::builds {

// One option of a meson options file: its type ("boolean", "feature", "combo", "array",
// "string", "integer") and, for combo and array, its choices.
struct MesonOption {
  std::string type;
  std::vector<std::string> choices;
};

// The options a meson options file declares, by name. Unparseable parts are skipped.
std::map<std::string, MesonOption> parse_meson_options(const std::string& text);

struct MesonPlanInputs {
  std::map<std::string, MesonOption> options;  // the tree's
  std::string source_dir, build_dir, prefix;   // absolute paths
  std::string native_file;                     // the file holding native_file_text(llvm_config)
  std::string glslang_version;                 // "12.0.0"; "" when glslangValidator is missing
  std::vector<std::string> extra;              // "-Dkey=value" given by the user, passed last
};

struct MesonPlan {
  std::vector<std::string> setup;    // meson setup ...
  std::vector<std::string> compile;  // ninja -C BUILD (jobs added by the caller)
  std::vector<std::string> install;  // meson install -C BUILD (or ninja install)
  std::vector<std::string> chosen;   // the -D options chosen from the tree's, in order
  std::vector<std::string> notes;    // what was left out and why ("lavapipe not built: ...")
};

// lavapipe needs glslang >= 12.2 in Mesa since 24.1; Debian 12 has 12.0.
bool glslang_builds_lavapipe(const std::string& glslang_version);

// The setup, compile and install command lines.
MesonPlan plan_meson_build(const MesonPlanInputs& in);

// A native file that pins LLVM to `llvm_config` (meson >= 1.3 prefers cmake's LLVM, which on
// Debian 12 finds the newest installed; cmake is disabled so that llvm-config is used). The path is
// written as one meson string (meson_string), so that no text of it becomes an entry of its own.
std::string native_file_text(const std::string& llvm_config);

// `text` as a meson string literal: in single quotes, with \ and ' escaped by a backslash and
// control characters as \xhh (so the literal is always on one line).
std::string meson_string(const std::string& text);

// UserError naming --llvm-config unless `path` is an existing executable regular file (a link to
// one counts) without control characters (a newline cannot be in a native file's string).
void check_llvm_config(const std::string& path);

}  // namespace ra::builds
