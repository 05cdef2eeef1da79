// `renderaudit builds build SOURCE`: a Mesa source tree (a git checkout, at a ref or as it is, or
// an unpacked source package with its patches applied) built with meson for the software drivers
// only (builds/meson_plan.h) into an install prefix, probed through OSMesa and EGL as
// `builds fetch` probes, and kept in the build cache with its provenance in build.json (source,
// commit or version, meson options, LLVM, compiler and meson versions, build time). Everything
// happens in a temporary folder inside the cache, moved into place by one rename: a failure
// (a missing tool or package, a failing configure, compile, install or probe) leaves the cache as
// it was and names the step, the missing package where meson says which, and the full log.
// A build of the same commit (or the same tree content) and the same options is reused, not
// rebuilt; meson uses ccache where it is installed.
//
// One writer per tree: a build holds the source tree's lock (builds/source_tree.h) from checkout
// to install. A build proves it is the commit it is named after: a git tree with a file git does not track
// (an untracked meson.options, as a checkout that failed half-way leaves) is refused for --ref
// (watch, bisect: every build of a commit) and built as it is only under a "-dirty" name; the
// tree's HEAD is read again after the install, and a build whose tree moved is not kept. build.json
// records the proof ("clean": the tree was the commit, nothing changed or added), and only a build
// with that proof is reused for its commit; an older one is built again.
//
// A build returned is held for use (BuildInUse, build_cache.h) for as long as its result lives, so
// that `builds remove` cannot delete it under a night or a bisection that draws with it.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "builds/build_cache.h"
#include "builds/build_fetch.h"
#include "builds/source_tree.h"

namespace ra::builds {

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
  // One meson build folder kept across builds of this tree with these options
  // (CACHE/.incremental/<key>): meson reconfigures by itself and ninja rebuilds only what the new
  // commit changed, as a hand-run `git bisect run` does. The install still lands in the commit's
  // own cache folder. False: a fresh build folder each time.
  bool incremental = false;
  bool source_locked = false;  // the caller holds lock_source_tree() of `source` already
  // With `ref`: check the tree's branch out again after the build. A bisection keeps the tree at
  // its steps' commits and restores it once at the end, so that an incremental build recompiles
  // only what differs between two steps.
  bool restore_ref = true;
};

struct SourceBuildResult {
  rundir::BuildRecord build;
  bool reused = false;
  double seconds = 0;     // configure + compile + install (0 when reused)
  std::string log;        // the build log (kept in the build folder as build.log)
  std::vector<std::string> notes;  // what the plan left out (lavapipe, OSMesa)
  std::shared_ptr<BuildInUse> in_use;  // the build held against `builds remove` (see the header)
};

// Builds (or reuses) and returns the build. `progress` receives one line per step
// ("configure", "compile", "install", "probe"). Throws UserError naming the failing step.
SourceBuildResult build_from_source(const SourceBuildOptions& options,
                                    const std::function<void(const std::string&)>& progress = {});

// The cached build of the tree `options.source` as it stands (its commit, clean) with these
// options, held for use and marked reused; none when the cache holds no such build. What a
// bisection reads after building a commit in a process of its own (`builds build`, a Slurm task).
std::optional<SourceBuildResult> cached_source_build(const SourceBuildOptions& options);

// The build of `commit` in `dir` (last night's, a bisection's end), held for use; built again
// with `options` at ref `commit` when `dir` no longer holds it (removed, the cache cleared) or
// holds no proof that it is that commit's. Throws UserError as build_from_source does.
SourceBuildResult use_source_build(const std::string& dir, const std::string& commit,
                                   SourceBuildOptions options,
                                   const std::function<void(const std::string&)>& progress = {});

// The cache name and reuse key of a build of `id` with `options` (tests).
std::string source_build_name(const SourceIdentity& id, const SourceBuildOptions& options);
std::string source_build_key(const SourceIdentity& id, const SourceBuildOptions& options);

// The Debian package that provides what a failed meson configure log says is missing
// ("Dependency \"libdrm\" not found" -> "libdrm-dev"), or "" when it names nothing known.
std::string missing_package_hint(const std::string& meson_log);

}  // namespace ra::builds
