// `renderaudit builds fetch SUITE` and `renderaudit builds list`: driver builds in the build cache
// (runner/build_fetch.h), drawn with as PLATFORM@BUILD.
#include <cstdio>

#include "app/commands.h"
#include "rundir/driver_build.h"
#include "runner/build_fetch.h"
#include "runner/source_build.h"
#include "util/errors.h"

namespace ra::app {
namespace {

void print_build(const runner::BuildSummary& b, bool files) {
  if (!b.damaged.empty()) {
    std::printf("%s  (damaged: %s)\n  folder: %s\n", b.name.c_str(), b.damaged.c_str(),
                b.dir.c_str());
    return;
  }
  if (b.origin == "source")
    std::printf("%s  (built from source: %s%s, built %s)\n  folder: %s\n", b.name.c_str(),
                b.version.empty() ? "" : b.version.c_str(),
                b.commit.empty() ? "" : (" at commit " + b.commit.substr(0, 12)).c_str(),
                b.fetched_utc.c_str(), b.dir.c_str());
  else
    std::printf("%s  (Debian %s, suite %s, fetched %s)\n  folder: %s\n", b.name.c_str(),
                b.debian_version.c_str(), b.suite.c_str(), b.fetched_utc.c_str(), b.dir.c_str());
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

}  // namespace

void add_commit_build_options(CLI::App* cmd, runner::SourceBuildOptions& build, bool& fresh_builds) {
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

void register_builds_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "builds",
      "Driver builds other than the installed Mesa: fetch a Debian suite's Mesa into the "
      "build cache, list the cache");
  cmd->require_subcommand(1);
  struct Options {
    runner::FetchOptions fetch;
    runner::SourceBuildOptions build;
    std::string list_cache;
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
    const runner::BuildSummary b = runner::fetch_build(opts->fetch);
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
  b->callback([opts, &exit_code] {
    for (std::string& v : opts->build.meson_options)
      if (v.rfind("-D", 0) != 0) v = "-D" + v;
    const runner::SourceBuildResult r = runner::build_from_source(
        opts->build,
        [](const std::string& line) { std::fprintf(stderr, "builds build: %s\n", line.c_str()); });
    print_build(r.build, false);
    std::printf("  %s\n",
                r.reused
                    ? "reused: same source and options"
                    : ("built in " + std::to_string(int(r.seconds)) + " s; log: " + r.log).c_str());
    exit_code = kExitOk;
  });
  auto* l = cmd->add_subcommand("list", "The builds in the build cache");
  l->add_option("--cache", opts->list_cache, "build cache folder");
  l->callback([opts, &exit_code] {
    const std::string cache =
        opts->list_cache.empty() ? rundir::build_cache_dir() : opts->list_cache;
    const std::vector<runner::BuildSummary> builds = runner::list_builds(cache);
    if (builds.empty())
      std::printf("no builds in %s (renderaudit builds fetch SUITE)\n", cache.c_str());
    for (const runner::BuildSummary& b : builds) print_build(b, false);
    exit_code = kExitOk;
  });
}

}  // namespace ra::app
