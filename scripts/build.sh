#!/usr/bin/env bash
# `make build` (and the targets that build more): cmake --build without the lines that say
# nothing, every target's "[ NN%] Built target X": a build with nothing to do prints nothing, and
# what is compiled, its warnings and errors are shown as they come (errors on stderr, unfiltered).
# Usage: scripts/build.sh BUILD_DIR JOBS [cmake --build options, e.g. --target T]
set -uo pipefail
build=$1 jobs=$2
shift 2
cmake --build "$build" -j "$jobs" "$@" |
  { grep --line-buffered -v -E '^\[ *[0-9]+%\] Built target |^Consolidate compiler generated dependencies of target ' || true; }
exit "${PIPESTATUS[0]}"
