#!/usr/bin/env bash
# `make run` as a user calls it with an experiment of their own (ctest make_run_lines): the line
# it prints names that experiment's platforms (not the embedded default's), the run's Markdown
# table stays in summary.md and the run is said in one line, `make report` ends with the finding
# and a line with the report's path and the time, in at most 7 lines (and the `make install` hint
# only until the program is installed), FAIL_ON_VIOLATIONS=1 judges the run's conformance at the
# end, the default target leaves the report as it is when neither the run nor the program changed
# (and makes it again when one did), `make build` prints nothing when there is nothing to build,
# a refused run folder is answered with the OUT= that make takes (an error in the experiment
# file is not), and `make driver-upgrade PER_VIEW=N` cuts the experiment to N per kind and view
# and refuses an N that is not a positive whole number before anything else.
# `make -o build`: the build is taken as it is (ctest runs beside other tests that use the binary;
# a relink under them would fail them).
# Usage: tests/scripts/make-run-test.sh BUILD_DIR
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
here=$(cd "$(dirname "$0")/../.." && pwd)
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
grep -qE "^run: $t/out: 30 primitives in 1 shards \(1 run now\), [0-9.]+ (s|min)" "$t/make.log" \
  || { cat "$t/make.log"; fail "no one-line summary of the run"; }

# `make report` on the same run, as a user reads it in a log (not a terminal): a line per stage,
# the finding from the data, and a last line with the report's path and the time it took.
rc=0
(cd "$here" && make -o build report BUILD="$build" EXPERIMENT="$t/mine.toml" OUT="$t/out" JOBS=2 \
  PREFIX="$t/not-installed") > "$t/report.log" 2>&1 || rc=$?
[ "$rc" = 0 ] || { cat "$t/report.log"; fail "make report exit $rc"; }
grep -qE "^finding: no violation \(no GL rule broken\) in [0-9,]+ primitives; [0-9.]+% drawn exactly" \
  "$t/report.log" || { cat "$t/report.log"; fail "no finding line"; }
grep -qE "^make report: done in [0-9]+ (s|min [0-9]+ s): $t/out/report/report.pdf \(and report.html\)$" \
  "$t/report.log" || { cat "$t/report.log"; fail "no last line with the path and the time"; }
finding_line=$(grep -n "^finding: " "$t/report.log" | cut -d: -f1)
[ "$finding_line" -ge "$(( $(wc -l < "$t/report.log") - 2 ))" ] \
  || { cat "$t/report.log"; fail "the finding is not at the end"; }
! grep -qE "Built target|^\| |^index: |^/" "$t/report.log" || { cat "$t/report.log"; fail "details printed"; }
lines=$(grep -vc "make install" "$t/report.log" || true)
[ "$lines" -le 7 ] || { cat "$t/report.log"; fail "make report printed $lines lines, more than 7"; }
# The `make install` hint until it has run (and renderaudit is not on PATH), never after it.
if ! command -v renderaudit > /dev/null; then
  grep -qF '`make install` puts it on PATH' "$t/report.log" \
    || { cat "$t/report.log"; fail "no make install hint before make install"; }
fi
mkdir -p "$t/installed/bin" && cp "$build/renderaudit" "$t/installed/bin/renderaudit"
quick=(-o build -o run -o analyze -o plot)  # the report stage alone: the run is analysed
rc=0
(cd "$here" && make "${quick[@]}" report BUILD="$build" EXPERIMENT="$t/mine.toml" OUT="$t/out" \
  PREFIX="$t/installed") > "$t/installed.log" 2>&1 || rc=$?
[ "$rc" = 0 ] || { cat "$t/installed.log"; fail "make report (installed) exit $rc"; }
! grep -qF "make install" "$t/installed.log" \
  || { cat "$t/installed.log"; fail "the make install hint after make install"; }

# FAIL_ON_VIOLATIONS=1: the run's conformance judged at the end of the report; this run breaks
# no rule, so it passes, and the report's last line still comes.
rc=0
(cd "$here" && make "${quick[@]}" report BUILD="$build" EXPERIMENT="$t/mine.toml" OUT="$t/out" \
  FAIL_ON_VIOLATIONS=1) > "$t/gate.log" 2>&1 || rc=$?
[ "$rc" = 0 ] || { cat "$t/gate.log"; fail "make report FAIL_ON_VIOLATIONS=1 exit $rc"; }
grep -qF "conformance: PASS: no violation" "$t/gate.log" || { cat "$t/gate.log"; fail "no conformance verdict"; }
grep -qE "^make report: done in " "$t/gate.log" || { cat "$t/gate.log"; fail "no last line"; }

# The default target (`make`) on a run that draws nothing new with a program not rebuilt: no
# analysis, figures or report again, the report untouched, a line saying so. The program is a copy
# here, so that its time can move without touching the build other tests use.
mkdir -p "$t/b"
cp -p "$build/renderaudit" "$build/renderaudit-worker" "$t/b/"
pdf=$t/out/report/report.pdf
default_make() {  # LOG [make arguments]
  local log=$1 rc=0
  shift
  (cd "$here" && make -o build BUILD="$t/b" EXPERIMENT="$t/mine.toml" OUT="$t/out" JOBS=2 \
    PREFIX="$t/installed" "$@") > "$log" 2>&1 || rc=$?
  [ "$rc" = 0 ] || { cat "$log"; fail "make (the default target) exit $rc"; }
}
made=$(stat -c %y "$pdf")
default_make "$t/same.log"
grep -qE "^make: up to date in [0-9]+ (s|min [0-9]+ s): $pdf \(and report.html\)" "$t/same.log" \
  || { cat "$t/same.log"; fail "a second make does not say the report is up to date"; }
! grep -qE "^(Wrote |plot: |report: |finding: |make report: )" "$t/same.log" \
  || { cat "$t/same.log"; fail "a second make analysed, plotted or reported again"; }
[ "$(stat -c %y "$pdf")" = "$made" ] || fail "a second make wrote the report again"
# FAIL_ON_VIOLATIONS=1 asks for a verdict: the stages run whatever the times.
default_make "$t/same-gate.log" FAIL_ON_VIOLATIONS=1
grep -qF "conformance: PASS: no violation" "$t/same-gate.log" \
  || { cat "$t/same-gate.log"; fail "make FAIL_ON_VIOLATIONS=1 gave no verdict on an unchanged run"; }
# A program built again, then a run that drew a shard again: the report is made again each time.
touch "$t/b/renderaudit"
made=$(stat -c %y "$pdf")
default_make "$t/program.log"
grep -qE "^make report: done in " "$t/program.log" || { cat "$t/program.log"; fail "a new program: no report"; }
[ "$(stat -c %y "$pdf")" != "$made" ] || fail "a new program: the report was not written again"
rm "$t/out/records/"*
made=$(stat -c %y "$pdf")
default_make "$t/run.log"
grep -qE "^run: $t/out: 30 primitives in 1 shards \(1 run now" "$t/run.log" \
  || { cat "$t/run.log"; fail "the shard was not drawn again"; }
grep -qE "^make report: done in " "$t/run.log" || { cat "$t/run.log"; fail "a changed run: no report"; }
[ "$(stat -c %y "$pdf")" != "$made" ] || fail "a changed run: the report was not written again"

# scripts/build.sh (`make build`): the "Built target" lines that a build with nothing to do
# consists of are left out, what is compiled is shown, and cmake's exit status is kept.
mkdir -p "$t/bin"
cat > "$t/bin/cmake" <<'FAKE'
#!/bin/sh
echo "[ 10%] Built target util"
echo "Consolidate compiler generated dependencies of target rundir"
[ -n "$FAKE_COMPILE" ] && echo "[ 20%] Building CXX object CMakeFiles/util.dir/util/x.cpp.o"
echo "[100%] Built target renderaudit"
exit ${FAKE_RC:-0}
FAKE
chmod +x "$t/bin/cmake"
out=$(PATH="$t/bin:$PATH" "$here/scripts/build.sh" "$t" 2)
[ -z "$out" ] || fail "a build with nothing to do printed: $out"
rc=0
out=$(FAKE_COMPILE=1 FAKE_RC=3 PATH="$t/bin:$PATH" "$here/scripts/build.sh" "$t" 2) || rc=$?
[ "$rc" = 3 ] || fail "build.sh exit $rc, not cmake's 3"
[ "$out" = "[ 20%] Building CXX object CMakeFiles/util.dir/util/x.cpp.o" ] \
  || fail "build.sh printed '$out', not the compile line alone"

mkdir -p "$t/foreign" && echo "not a run" > "$t/foreign/notes.txt"
rc=0
make -s -o build -C "$here" run BUILD="$build" EXPERIMENT="$t/mine.toml" OUT="$t/foreign" JOBS=2 \
  > "$t/make.log" 2>&1 || rc=$?
[ "$rc" != 0 ] || fail "a foreign run folder was accepted"
grep -qF "with make, OUT=DIR names the run folder (now $t/foreign)" "$t/make.log" \
  || { cat "$t/make.log"; fail "no OUT= advice"; }

# An error in the experiment file is not about the run folder: no OUT= advice.
printf 'name = "bad"\nseed = 1\nplatforms = ["osmesa-softpipe"]\n[views]\norientatons = 1\n' \
  > "$t/bad.toml"
rc=0
make -s -o build -C "$here" run BUILD="$build" EXPERIMENT="$t/bad.toml" OUT="$t/bad" JOBS=2 \
  > "$t/bad.log" 2>&1 || rc=$?
[ "$rc" = 2 ] || { cat "$t/bad.log"; fail "a broken experiment file: exit $rc, not 2"; }
grep -qF "$t/bad.toml:" "$t/bad.log" || { cat "$t/bad.log"; fail "the error is not located"; }
! grep -qF "OUT=DIR" "$t/bad.log" || { cat "$t/bad.log"; fail "OUT= advice for an experiment-file error"; }
# `make driver-upgrade PER_VIEW=N`: N checked first (no fetch, no run), the cut copy as asked.
for bad in abc 0 -5 1.5 0100 "1 2" 100000001; do
  rc=0
  (cd "$here" && make -o build driver-upgrade PER_VIEW="$bad" OUT="$t/du") > "$t/du.log" 2>&1 || rc=$?
  [ "$rc" = 2 ] || { cat "$t/du.log"; fail "make driver-upgrade PER_VIEW=$bad: exit $rc, not 2"; }
  grep -qF "make driver-upgrade: PER_VIEW=$bad is not a number of primitives per kind and view" \
    "$t/du.log" || { cat "$t/du.log"; fail "PER_VIEW=$bad: no message saying why"; }
  ! grep -qF "driver-upgrade: step" "$t/du.log" || fail "PER_VIEW=$bad: the upgrade started"
  [ ! -e "$t/du" ] && [ ! -e "$t/du.toml" ] || fail "PER_VIEW=$bad: files written"
done
"$here/scripts/cut-experiment.sh" "$here/experiments/driver-upgrade.toml" 7 "$t/cut.toml" > /dev/null
cut=$(grep -E '^(name|points|lines|triangles|shard_size) = ' "$t/cut.toml" | tr '\n' ' ')
[ "$cut" = 'name = "driver-upgrade-7" points = 7 lines = 7 triangles = 7 shard_size = 7 ' ] \
  || fail "the cut experiment reads: $cut"
diff <(grep -vE '^(name|points|lines|triangles|shard_size) = ' "$here/experiments/driver-upgrade.toml") \
  <(grep -vE '^(name|points|lines|triangles|shard_size) = ' "$t/cut.toml") > /dev/null \
  || fail "the cut experiment differs in more than its name, counts and shard size"

echo "make-run-test: the platform line, a quiet run, the OUT= advice where it fits, make report's lines and hints, make's report kept while nothing changed, a quiet build, PER_VIEW"
