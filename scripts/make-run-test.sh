#!/usr/bin/env bash
# `make run` as a user calls it with an experiment of their own (ctest make_run_lines): the line
# it prints names that experiment's platforms (not the embedded default's), the run's Markdown
# table stays in summary.md, and a refused run folder is answered with the OUT= that make takes.
# `make -o build`: the build is taken as it is (ctest runs beside other tests that use the binary;
# a relink under them would fail them).
# Usage: scripts/make-run-test.sh BUILD_DIR
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
here=$(cd "$(dirname "$0")/.." && pwd)
t=$(mktemp -d /tmp/renderaudit-make-run-test-XXXXXX)
trap '[ -n "${KEEP:-}" ] || rm -rf "$t"' EXIT
fail() { echo "make-run-test: FAIL: $*" >&2; exit 1; }

cat > "$t/mine.toml" <<EOF
name = "mine"
seed = 2
platforms = ["osmesa-softpipe"]
[views]
orientations = 1
fov_deg = [30]
windows = [64]
near = 0.01
far = 10.0
[primitives]
points = 30
EOF
rc=0
make -s -o build -C "$here" run BUILD="$build" EXPERIMENT="$t/mine.toml" OUT="$t/out" JOBS=2 \
  > "$t/make.log" 2>&1 || rc=$?
[ "$rc" = 0 ] || { cat "$t/make.log"; fail "make run exit $rc"; }
grep -qF "renderaudit: $t/mine.toml draws with osmesa-softpipe" "$t/make.log" \
  || { cat "$t/make.log"; fail "no line naming the experiment's platform"; }
! grep -qF "osmesa-llvmpipe" "$t/make.log" || { cat "$t/make.log"; fail "names the default platform"; }
! grep -qF "| platform |" "$t/make.log" || fail "the summary's table was printed"
grep -qF "summary: $t/out/summary.md" "$t/make.log" || fail "the summary's path is not said"

mkdir -p "$t/foreign" && echo "not a run" > "$t/foreign/notes.txt"
rc=0
make -s -o build -C "$here" run BUILD="$build" EXPERIMENT="$t/mine.toml" OUT="$t/foreign" JOBS=2 \
  > "$t/make.log" 2>&1 || rc=$?
[ "$rc" != 0 ] || fail "a foreign run folder was accepted"
grep -qF "with make, OUT=DIR names the run folder (now $t/foreign)" "$t/make.log" \
  || { cat "$t/make.log"; fail "no OUT= advice"; }
echo "make-run-test: the platform line, a quiet run, the OUT= advice"
