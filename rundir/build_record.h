// A driver build's folder and its build.json: the one reader of that document, and the walk of the
// build cache. A build is a folder of unpacked Mesa libraries (Debian packages `dpkg-deb -x` into
// it, or a meson install prefix) with a build.json saying where it came from; experiments name it
// (`PLATFORM@NAME`, `[builds.NAME]`), and builds/ makes, probes and removes it.
#pragma once

#include <string>
#include <vector>

namespace ra::rundir {

// build.json's document name and version (rundir/manifest.h's document header).
inline constexpr const char* kBuildDocument = "driver-build";
inline constexpr int kBuildDocumentVersion = 1;

// The folder where `renderaudit builds fetch` and `builds build` keep builds:
// $RENDERAUDIT_BUILD_CACHE, else $XDG_CACHE_HOME/renderaudit/builds, else
// ~/.cache/renderaudit/builds.
std::string build_cache_dir();

// What a build folder holds (its build.json).
struct BuildRecord {
  std::string name;    // "mesa-25.0.7": the upstream version of its libosmesa6, or the source's
  std::string dir;     // its folder in the cache
  std::string suite;   // the Debian suite it came from ("" for a source build)
  std::string debian_version;  // "25.0.7-2~bpo12+1"
  std::string osmesa_version, egl_version;  // GL_VERSION through each back end ("" if it cannot)
  std::string fetched_utc;                  // when (built, for a source build)
  std::vector<std::string> files;           // the shared libraries, relative to dir
  // list_cached_builds: "" for a build whose build.json reads, else "FOLDER/build.json: why it
  // does not" (the other fields are then empty but name and dir, name being the folder's).
  std::string damaged;
  std::string origin;   // "Debian" (builds fetch) or "source" (builds build)
  // A source build (origin "source"): its tree, git commit ("" when not from git), VERSION
  // ("25.1.0-devel"), whether the tree was a git checkout with nothing changed or untracked (only
  // then is the build the commit's), and the reuse key of its inputs (builds/source_build.h).
  std::string source;
  std::string commit;
  std::string version;
  bool from_git = false;
  bool clean = false;
  std::string key;
  // list_cached_builds: the name build.json records when the folder was renamed since (the
  // folder's name is the build's: PLATFORM@FOLDER draws it, `builds remove FOLDER` removes it);
  // else "".
  std::string recorded_name;
};

// DIR/build.json: where a build folder keeps its record (written by builds/ with
// document_header(kBuildDocument, kBuildDocumentVersion)).
std::string build_record_path(const std::string& dir);

// Whether `dir` is a build folder of a cache: not hidden (unfinished work, incremental build
// folders) and holding a build.json.
bool is_build_folder(const std::string& dir);

// The build.json of folder `dir`. Throws util::UserError naming the file when it is missing, not
// JSON, nested too deep or of another document.
BuildRecord read_build_record(const std::string& dir);

// The builds in the cache `cache` (default build_cache_dir()), by folder name; those whose
// build.json cannot be read are listed with `damaged` set. UserError when `cache` is a file; an
// absent cache holds no builds.
std::vector<BuildRecord> list_cached_builds(const std::string& cache = "");

// The cache folder of the build most recently fetched from Debian suite `suite`, or "" when the
// cache holds none.
std::string cached_build_of_suite(const std::string& suite);

// Where a build folder keeps its shared libraries: DIR/usr/lib/<multiarch>, DIR/usr/lib,
// DIR/lib/<multiarch> (a meson install prefix), DIR/lib or DIR itself, the first that holds
// libOSMesa.so.8, libEGL_mesa.so.0 or libvulkan_lvp.so; DIR/usr/lib/<multiarch> when none does
// (the message then names the library missing there).
std::string build_library_dir(const std::string& dir);

}  // namespace ra::rundir
