// Driver builds: a Mesa other than the installed one, drawn with by name (`osmesa-llvmpipe@NAME`).
// A build is a folder of unpacked libraries (e.g. Debian's libosmesa6, mesa-libgallium,
// libegl-mesa0, libgbm1, libdrm2 of another suite, `dpkg-deb -x` into one folder); nothing is
// installed. A process that draws with a build loads its libraries by absolute path before the GL
// library asks for them by soname, so the environment (LD_LIBRARY_PATH, RENDERAUDIT_LIBOSMESA)
// cannot swap in another driver: glibc hands an already loaded soname to every later dlopen, and
// glvnd's `libEGL_mesa.so.0` is then the build's. One build per process: Mesa cannot be unloaded.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "rundir/platform_spec.h"

namespace ra::rundir {

// The first words of every refusal to draw with another driver than the one that made a run's
// records (platforms/renderer_check.h); the processes that start drawers (the coordinator, the
// audit's re-renders) recognise a child's refusal by them.
inline constexpr const char* kDriverMismatch = "driver mismatch";

// The folder where `renderaudit builds fetch` keeps builds: $RENDERAUDIT_BUILD_CACHE, else
// $XDG_CACHE_HOME/renderaudit/builds, else ~/.cache/renderaudit/builds.
std::string build_cache_dir();

// The cache folder of the build most recently fetched from Debian suite `suite` (its build.json
// says so), or "" when the cache holds none.
std::string cached_build_of_suite(const std::string& suite);

// Where a build folder keeps its shared libraries: DIR/usr/lib/<multiarch>, DIR/usr/lib,
// DIR/lib/<multiarch> (a meson install prefix), DIR/lib or DIR itself, the first that holds libOSMesa.so.8, libEGL_mesa.so.0 or libvulkan_lvp.so; DIR/usr/lib/<multiarch>
// when none does (the message then names the library missing there).
std::string build_library_dir(const std::string& dir);

// One library a process has loaded, with its content fingerprint (FNV-1a 64 of the file's bytes,
// 16 hex digits): equal fingerprints mean the same file whatever its path.
struct LoadedLibrary {
  std::string path;
  std::string fnv1a64;
};

// The driver libraries this process has loaded now (Mesa, glvnd, gallium, LLVM, libdrm, gbm, DRI
// drivers, OSMesa, EGL, GL), in load order, each with its fingerprint.
std::vector<LoadedLibrary> loaded_driver_libraries();

// Loads `spec`'s build (spec.build non-empty) for its back end: the back end's library
// (libOSMesa.so.8, libEGL_mesa.so.0, lavapipe's libvulkan_lvp.so) and the build's libraries it
// needs, dependencies first. Does nothing for the installed driver (spec.build empty) except
// remember that this process uses it. Throws UserError when the build folder lacks the library
// (naming the folder and how to fetch a build), or when this process already loaded another
// build or the installed driver.
void load_driver_build(const PlatformSpec& spec);

// The soname and needed sonames of an ELF shared library (tests and the loader); empty soname
// when `path` is not a readable 64-bit ELF file.
struct ElfDependencies {
  std::string soname;
  std::vector<std::string> needed;
};
ElfDependencies read_elf_dependencies(const std::string& path);

}  // namespace ra::rundir
