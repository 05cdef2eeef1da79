#!/usr/bin/env bash
# Whether a build folder belongs to this source tree (the Makefile's build step runs it first).
# CMake writes absolute paths into a build folder: CMakeCache.txt names the source tree
# (CMAKE_HOME_DIRECTORY) and the folder itself (CMAKE_CACHEFILE_DIR), and the Makefiles it
# generates compile that source tree into that folder. A checkout copied or moved with its build
# folder, or a build folder moved on its own, would make `cmake --build` compile the original tree
# without a word; this check stops first and says which tree the folder belongs to.
# Exit 0: no CMakeCache.txt yet, or it names this tree and this folder; 2: it names others.
# Usage: scripts/check-build-tree.sh [BUILD_DIR]   (default build)
set -euo pipefail
build=${1:-build}
here=$(cd "$(dirname "$0")/.." && pwd -P)
cache=$build/CMakeCache.txt
[ -f "$cache" ] || exit 0

value() { sed -n "s/^$1=//p" "$cache"; }
# A path as the file system resolves it (symbolic links followed) where it exists, else as written.
real() { if [ -d "$1" ]; then (cd "$1" && pwd -P); else printf '%s\n' "$1"; fi; }

source_dir=$(value 'CMAKE_HOME_DIRECTORY:INTERNAL')
[ -n "$source_dir" ] || source_dir=$(value 'renderaudit_SOURCE_DIR:STATIC')
made_in=$(value 'CMAKE_CACHEFILE_DIR:INTERNAL')
[ -n "$made_in" ] || made_in=$(sed -n 's/^# For build in directory: //p' "$cache")
advice="Remove it to configure a build here (rm -rf $build), or build into another folder (make BUILD=other-folder)."

if [ -n "$source_dir" ] && [ "$(real "$source_dir")" != "$here" ]; then
  echo "make: $build/ belongs to the source tree $source_dir (its CMakeCache.txt), not to this one ($here): a copied or moved checkout keeps CMake's absolute paths, and cmake --build would compile $source_dir instead. $advice" >&2
  exit 2
fi
if [ -n "$made_in" ] && [ "$(real "$made_in")" != "$(real "$build")" ]; then
  echo "make: $build/ was configured as the build folder $made_in (its CMakeCache.txt): a moved or copied build folder keeps CMake's absolute paths, and cmake --build would build into $made_in. $advice" >&2
  exit 2
fi
