// `renderaudit builds build SOURCE`: a Mesa source tree (a git checkout, at a ref or as it is, or
// an unpacked source package with its patches applied) built with meson for the software drivers
// only (runner/meson_plan.h) into an install prefix, probed through OSMesa and EGL as
// `builds fetch` probes, and kept in the build cache with its provenance in build.json (source,
// commit or version, meson options, LLVM, compiler and meson versions, build time). Everything
// happens in a temporary folder inside the cache, moved into place by one rename: a failure
// (a missing tool or package, a failing configure, compile, install or probe) leaves the cache as
// it was and names the step, the missing package where meson says which, and the full log.
// A build of the same commit (or source version) and the same options is reused, not rebuilt;
// meson uses ccache where it is installed.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "runner/build_fetch.h"

namespace ra::runner {

struct SourceBuildOptions {
  std::string source;   // the Mesa source tree
  std::string ref;      // git ref to check out first (the tree must be clean); "": as it is
  std::string name;     // cache name; "": mesa-<commit 12> (git) or mesa-<VERSION>-src
  std::string cache;    // "": platforms::build_cache_dir()
  std::string llvm_config = "/usr/bin/llvm-config-15";  // one LLVM for every build
  std::vector<std::string> meson_options;  // extra "-Dkey=value", passed after the chosen ones
  // Instead of meson: a shell command run in the source tree that installs a build into
  // $RENDERAUDIT_BUILD_PREFIX (tests, and trees meson cannot build). Part of the reuse key.
  std::string build_command;
  std::string meson = "meson";  // the meson program (a path, or a name looked up in PATH)
  unsigned jobs = 0;    // ninja -j; 0: the number of cores
  bool probe = true;    // probe OSMesa and EGL before keeping the build
  bool reuse = true;    // reuse a cached build of the same commit and options
};

// Where a source tree stands: git commit (and whether uncommitted changes make it another
// source), or the version of an unpacked source package.
struct SourceIdentity {
  std::string source;        // the tree's folder, canonical
  bool git = false;
  bool dirty = false;        // git: tracked files differ from the commit
  std::string commit;        // full hash ("" when not git)
  std::string subject, date; // the commit's
  std::string version;       // the tree's VERSION file ("25.1.0-devel")
  std::string debian_version;  // debian/changelog's first entry, when present
  std::string patches;       // debian/patches/series (the patches a source package applies)
};
SourceIdentity identify_source(const std::string& source_dir);

struct SourceBuildResult {
  BuildSummary build;
  bool reused = false;
  double seconds = 0;     // configure + compile + install (0 when reused)
  std::string log;        // the build log (kept in the build folder as build.log)
  std::vector<std::string> notes;  // what the plan left out (lavapipe, OSMesa)
};

// Builds (or reuses) and returns the build. `progress` receives one line per step
// ("configure", "compile", "install", "probe"). Throws UserError naming the failing step.
SourceBuildResult build_from_source(const SourceBuildOptions& options,
                                    const std::function<void(const std::string&)>& progress = {});

// The cache name and reuse key of a build of `id` with `options` (tests).
std::string source_build_name(const SourceIdentity& id, const SourceBuildOptions& options);
std::string source_build_key(const SourceIdentity& id, const SourceBuildOptions& options);

// The Debian package that provides what a failed meson configure log says is missing
// ("Dependency \"libdrm\" not found" -> "libdrm-dev"), or "" when it names nothing known.
std::string missing_package_hint(const std::string& meson_log);

}  // namespace ra::runner
