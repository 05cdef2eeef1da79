// Loading a driver build into this process: a Mesa other than the installed one, drawn with by
// name (`osmesa-llvmpipe@NAME`), its libraries unpacked into a folder (rundir/build_record.h);
// nothing is installed. A process that draws with a build loads its libraries by absolute path
// before the GL library asks for them by soname, so the environment (LD_LIBRARY_PATH,
// RENDERAUDIT_LIBOSMESA) cannot swap in another driver: glibc hands an already loaded soname to
// every later dlopen, and glvnd's `libEGL_mesa.so.0` is then the build's. One build per process:
// Mesa cannot be unloaded.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "rundir/platform_spec.h"

namespace ra::platforms {

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
void load_driver_build(const rundir::PlatformSpec& spec);

// The soname and needed sonames of an ELF shared library (tests and the loader); empty soname
// when `path` is not a readable 64-bit ELF file.
struct ElfDependencies {
  std::string soname;
  std::vector<std::string> needed;
};
ElfDependencies read_elf_dependencies(const std::string& path);

}  // namespace ra::platforms
