// `renderaudit builds fetch SUITE`: a Debian suite's Mesa as a driver build in the build cache
// (rundir/build_record.h), with apt's own tools and nothing installed: a private apt
// configuration (its own sources list, lists and archive folders), `apt-get update`,
// `apt-get download` of the Mesa packages, `dpkg-deb -x` of each into one folder, a probe of the
// folder's OSMesa and EGL, then one rename into the cache. Everything happens in a temporary
// folder inside the cache, so a failure (no network, a suite or package that does not exist, a
// build that cannot draw) leaves the cache as it was.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rundir/build_record.h"

namespace ra::builds {

struct FetchOptions {
  std::string suite;                               // e.g. "bookworm-backports"
  std::string mirror = "http://deb.debian.org/debian";
  std::string cache;                               // empty: build_cache_dir()
};

// The Mesa packages a build is made of: those every suite must have, and those only some releases
// split out (libglapi-mesa and libgl1-mesa-dri before Mesa 24, mesa-libgallium after).
const std::vector<std::string>& required_build_packages();
const std::vector<std::string>& optional_build_packages();

// Probes osmesa-llvmpipe and egl-llvmpipe with the build folder `dir` (named s.name), each in a
// child; sets s.osmesa_version and s.egl_version ("" when one cannot draw) and returns the GL
// strings or errors as build.json keeps them ({"osmesa": {...}, "egl": {...}}).
nlohmann::json probe_build(rundir::BuildRecord& s, const std::string& dir);

// The shared libraries of a build folder, relative to it, sorted.
std::vector<std::string> build_libraries(const std::string& dir);

// Whether `url` is one Debian archive address as apt's sources list takes it: http:// or
// https:// with a host, or file:/ with a path; printable ASCII without spaces, quotes, brackets or
// control characters (a newline would add a source line of its own, a '[' options to this one).
bool is_mirror_url(const std::string& url);

// Fetches, unpacks, probes and moves the build into the cache (replacing a build of the same
// name). Throws UserError for an unreachable suite, a missing package, a missing tool (apt-get,
// dpkg-deb) or a build that cannot draw; the cache is then unchanged.
rundir::BuildRecord fetch_build(const FetchOptions& options);

// Makes the cache folder; UserError naming it when it is a file or cannot be made.
void require_cache_folder(const std::string& cache);

}  // namespace ra::builds
