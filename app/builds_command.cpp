// `renderaudit builds fetch SUITE`, `builds build SOURCE`, `builds list` and `builds remove
// NAME...`: driver builds in the build cache (builds/build_fetch.h, builds/source_build.h), drawn
// with as PLATFORM@BUILD; their sizes and removal in builds/build_cache.h.
#include <algorithm>
#include <cstdio>

#include "app/commands.h"
#include "rundir/build_record.h"
#include "builds/build_cache.h"
#include "builds/build_fetch.h"
#include "builds/source_build.h"
#include "util/errors.h"
#include "util/interrupt.h"

namespace ra::app {
namespace {

// A build's first line starts with its name and its size on disk, the name padded to `width` and
// the size to 7 characters, so that the sizes of a list form a column.
void print_build(const rundir::BuildRecord& b, bool files, std::size_t width = 0) {
  std::string size = builds::size_text(builds::disk_usage(b.dir));
  size.insert(0, size.size() < 7 ? 7 - size.size() : 0, ' ');  // "999 MiB": right-aligned
  const std::string head =
      b.name + std::string(width > b.name.size() ? width - b.name.size() : 0, ' ') + "  " + size;
  if (!b.damaged.empty()) {
    std::printf("%s  (damaged: %s)\n  folder: %s\n", head.c_str(), b.damaged.c_str(),
                b.dir.c_str());
    return;
  }
  if (b.origin == "source")
    std::printf("%s  (built from source: %s%s, built %s)\n  folder: %s\n", head.c_str(),
                b.version.empty() ? "" : b.version.c_str(),
                b.commit.empty() ? "" : (" at commit " + b.commit.substr(0, 12)).c_str(),
                b.fetched_utc.c_str(), b.dir.c_str());
  else
    std::printf("%s  (Debian %s, suite %s, fetched %s)\n  folder: %s\n", head.c_str(),
                b.debian_version.c_str(), b.suite.c_str(), b.fetched_utc.c_str(), b.dir.c_str());
  if (!b.recorded_name.empty())
    std::printf("  renamed by hand: its build.json calls it %s\n", b.recorded_name.c_str());
  std::printf("  OSMesa GL_VERSION: %s\n  EGL    GL_VERSION: %s\n",
              b.osmesa_version.empty() ? "(cannot draw)" : b.osmesa_version.c_str(),
              b.egl_version.empty() ? "(cannot draw)" : b.egl_version.c_str());
  if (files)
    for (const std::string& f : b.files) std::printf("  %s\n", f.c_str());
  std::printf(
      "  platforms: osmesa-llvmpipe@%s, osmesa-softpipe@%s, egl-llvmpipe@%s, "
      "egl-softpipe@%s\n",
      b.name.c_str(), b.name.c_str(), b.name.c_str(), b.name.c_str());
}

// What the cache holds in all, the builds and what else takes room there.
void print_cache_total(const std::string& cache, std::size_t n_builds) {
  const builds::CacheUsage u = builds::cache_usage(cache);
  std::string parts = std::to_string(n_builds) + (n_builds == 1 ? " build " : " builds ") +
                      builds::size_text(u.builds);
  if (u.incremental)
    parts += ", meson build folders kept for incremental builds (.incremental) " +
             builds::size_text(u.incremental);
  if (u.unfinished)
    parts += ", unfinished fetches, builds or removals " + builds::size_text(u.unfinished);
  std::printf("total %s in %s: %s\n", builds::size_text(u.total).c_str(), cache.c_str(),
              parts.c_str());
}

}  // namespace

void add_commit_build_options(CLI::App* cmd, builds::SourceBuildOptions& build, bool& fresh_builds) {
  cmd->add_option("--cache", build.cache, "build cache folder");
  cmd->add_option("--llvm-config", build.llvm_config, "the LLVM every build uses")
      ->capture_default_str();
  cmd->add_option("--meson-option,-D", build.meson_options, "extra meson option KEY=VALUE");
  cmd->add_option("--build-command", build.build_command,
                  "a shell command that installs the checked-out commit's driver into "
                  "$RENDERAUDIT_BUILD_PREFIX instead of meson");
  cmd->add_flag("--fresh-builds", fresh_builds,
                "a new meson build folder for every commit (default: one incremental folder)");
}

void add_speed_attribution_options(CLI::App* cmd, triage::BisectSpeedOptions& speed,
                                   const std::string& what) {
  cmd->add_flag("--speed", speed.enabled, what);
  cmd->add_option("--speed-repeats", speed.repeats,
                  "rounds of fresh processes per side in each timing, default 10")
      ->check(CLI::Range(2, 1000));
  cmd->add_option("--speed-primitives", speed.per_view,
                  "primitives of each kind and view timed, default 100")
      ->check(CLI::Range(uint64_t(6), uint64_t(1000000)));
  cmd->add_option("--speed-threshold", speed.threshold,
                  "a time change counts only when its whole 95% interval lies beyond this "
                  "fraction, default 0.05")
      ->check(CLI::Range(0.0, 10.0));
}

void check_speed_options(const std::string& command, const triage::BisectSpeedOptions& speed) {
  const triage::BisectSpeedOptions d;
  if (!speed.enabled &&
      (speed.repeats != d.repeats || speed.per_view != d.per_view || speed.threshold != d.threshold))
    throw util::UserError(command + ": --speed-repeats, --speed-primitives and --speed-threshold "
                          "go with --speed");
}

void register_builds_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "builds",
      "Driver builds other than the installed Mesa: fetch a Debian suite's Mesa or build a Mesa "
      "source tree into the build cache, list the cache with its size, remove builds");
  cmd->require_subcommand(1);
  struct Options {
    builds::FetchOptions fetch;
    builds::SourceBuildOptions build;
    std::string list_cache;
    std::string remove_cache;
    std::vector<std::string> remove_names;
  };
  const auto opts = std::make_shared<Options>();  // alive as long as the callbacks
  auto* f = cmd->add_subcommand(
      "fetch",
      "Fetch the Mesa packages of a Debian suite (e.g. bookworm-backports) with apt-get download "
      "through a private apt configuration (nothing installed), unpack them with dpkg-deb, probe "
      "OSMesa and EGL, and keep the build in the cache as mesa-VERSION");
  f->add_option("suite", opts->fetch.suite, "Debian suite, e.g. bookworm-backports")->required();
  f->add_option("--mirror", opts->fetch.mirror, "Debian archive")->capture_default_str();
  f->add_option("--cache", opts->fetch.cache,
                "build cache folder (default $RENDERAUDIT_BUILD_CACHE, else "
                "~/.cache/renderaudit/builds)");
  f->callback([opts, &exit_code] {
    const rundir::BuildRecord b = builds::fetch_build(opts->fetch);
    print_build(b, true);
    exit_code = kExitOk;
  });
  auto* b = cmd->add_subcommand(
      "build",
      "Build a Mesa source tree (a git checkout, at --ref or as it is, or an unpacked source "
      "package with its patches applied) with meson, software drivers only (llvmpipe, softpipe; "
      "lavapipe where glslang >= 12.2), into the build cache with its provenance; probe OSMesa "
      "and EGL. A build of the same commit and options is reused. Needs "
      "scripts/install-mesa-build-deps.sh once");
  b->add_option("source", opts->build.source, "Mesa source tree")->required();
  b->add_option("--ref", opts->build.ref,
                "git ref to build (checked out for the build, then back)");
  b->add_option("--name", opts->build.name,
                "build name (default mesa-<commit 12> or mesa-<VERSION>-src)");
  b->add_option("--cache", opts->build.cache, "build cache folder");
  b->add_option("--llvm-config", opts->build.llvm_config, "the LLVM every build uses")
      ->capture_default_str();
  b->add_option("--meson-option,-D", opts->build.meson_options,
                "extra meson option, KEY=VALUE (repeatable), passed after the chosen ones");
  b->add_option("--build-command", opts->build.build_command,
                "a shell command that installs a build into $RENDERAUDIT_BUILD_PREFIX instead of "
                "meson (run in the source tree)");
  b->add_option("--jobs,-j", opts->build.jobs, "ninja jobs (default: the number of cores)");
  b->add_flag(
      "--rebuild", [opts](int64_t) { opts->build.reuse = false; },
      "build even when a build of the same commit and options is cached");
  b->add_flag("--incremental", opts->build.incremental,
              "one meson build folder kept for this tree and options (CACHE/.incremental): ninja "
              "rebuilds only what the next commit changed");
  b->add_flag(
      "--no-probe", [opts](int64_t) { opts->build.probe = false; },
      "keep the build without probing OSMesa and EGL (its user draws with it: a bisection)");
  b->callback([opts, &exit_code] {
    for (std::string& v : opts->build.meson_options)
      if (v.rfind("-D", 0) != 0) v = "-D" + v;
    // A signal stops the build's whole process group (a bisection cancels a build it no longer
    // needs with SIGTERM).
    util::InterruptScope interrupts;
    builds::SourceBuildResult r;
    try {
      r = builds::build_from_source(opts->build, [](const std::string& line) {
        std::fprintf(stderr, "builds build: %s\n", line.c_str());
      });
    } catch (const util::UserError&) {
      if (util::interrupt_signal() == 0) throw;
      std::fprintf(stderr, "builds build: interrupted; the build cache is unchanged\n");
      exit_code = 128 + util::interrupt_signal();
      return;
    }
    print_build(r.build, false);
    std::printf("  %s\n",
                r.reused
                    ? "reused: same source and options"
                    : ("built in " + std::to_string(int(r.seconds)) + " s; log: " + r.log).c_str());
    exit_code = kExitOk;
  });
  auto* l = cmd->add_subcommand(
      "list",
      "The builds in the build cache, each with its size on disk (as du counts it), and what the "
      "cache holds in all");
  l->add_option("--cache", opts->list_cache, "build cache folder");
  l->callback([opts, &exit_code] {
    const std::string cache =
        opts->list_cache.empty() ? rundir::build_cache_dir() : opts->list_cache;
    const std::vector<rundir::BuildRecord> builds = rundir::list_cached_builds(cache);
    if (builds.empty())
      std::printf("no builds in %s (renderaudit builds fetch SUITE)\n", cache.c_str());
    std::size_t width = 0;
    for (const rundir::BuildRecord& b : builds) width = std::max(width, b.name.size());
    for (const rundir::BuildRecord& b : builds) print_build(b, false, width);
    print_cache_total(cache, builds.size());
    if (!builds.empty()) std::printf("renderaudit builds remove NAME... deletes builds\n");
    exit_code = kExitOk;
  });
  auto* r = cmd->add_subcommand(
      "remove",
      "Delete builds from the build cache: each is first renamed aside inside the cache, then "
      "deleted, so an interrupted removal never leaves a build that looks whole. Refuses a name "
      "the cache does not hold (listing those it holds) and a build whose source tree a build, "
      "bisection or watch night is using now; removes nothing then");
  r->add_option("name", opts->remove_names, "build names (renderaudit builds list)")->required();
  r->add_option("--cache", opts->remove_cache, "build cache folder");
  r->callback([opts, &exit_code] {
    const std::string cache =
        opts->remove_cache.empty() ? rundir::build_cache_dir() : opts->remove_cache;
    for (const builds::RemovedBuild& b : builds::remove_builds(cache, opts->remove_names)) {
      std::printf("removed %s (%s)\n", b.name.c_str(), builds::size_text(b.bytes).c_str());
      if (!b.left.empty())
        std::fprintf(stderr,
                     "builds remove: %s is no longer a build, but its files in %s could not all "
                     "be deleted; the next `builds remove` deletes them\n",
                     b.name.c_str(), b.left.c_str());
    }
    print_cache_total(cache, rundir::list_cached_builds(cache).size());
    exit_code = kExitOk;
  });
}

}  // namespace ra::app
