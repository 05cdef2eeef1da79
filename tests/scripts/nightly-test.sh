#!/usr/bin/env bash
# `scripts/nightly.sh` over four nights of a small experiment (ctest nightly_nights):
#   night 1: no baseline: "baseline established: nothing compared" (exit 0) in the audit, the
#            report and junit.xml (every case skipped); nothing reads as a comparison (no
#            "compared N", "unchanged", tests or class counts; never UNCHANGED or PASS); the
#            history records the night as the baseline; the terminal says where the baseline is,
#            in a few lines;
#   night 2: the same experiment: unchanged (exit 0), PASS; the terminal gives the verdict with its
#            counts and the files in a few lines (no table, no figure paths);
#   night 3: the experiment edited: exit 2, the differing lines and the --promote line said (once), no
#            "verdict in" a file that was not written, the report says "no verdict" and why;
#   night 4: after --promote of night 3: unchanged against it.
# Usage: tests/scripts/nightly-test.sh BUILD_DIR
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
here=$(cd "$(dirname "$0")/../.." && pwd)
t=$(mktemp -d /tmp/renderaudit-nightly-test-XXXXXX)
trap '[ -n "${KEEP:-}" ] || rm -rf "$t"' EXIT
fail() { echo "nightly-test: FAIL: $*" >&2; exit 1; }

experiment() {  # $1: points per view
  cat > "$t/nightly.toml" <<EOF
name = "nightly-test"
seed = 11
platforms = ["osmesa-llvmpipe"]
[views]
orientations = 1
fov_deg = [30]
windows = [128]
near = 0.01
far = 10.0
[primitives]
points = $1
lines = 40
EOF
}

night() {  # runs one night; its exit code in $rc, its output in $t/night.log
  rc=0
  # Drawing time is judged (NIGHTLY_SPEED=warn), but these nights test the verdicts of pixels: a
  # slower group on a busy machine must not flip them (the speed verdict has tests of its own).
  (cd "$here" && NIGHTLY_EXPERIMENT="$t/nightly.toml" NIGHTLY_DIR="$t/nightly" BUILD="$build" \
     JOBS=2 NIGHTLY_SPEED=warn scripts/nightly.sh) > "$t/night.log" 2>&1 || rc=$?
  sleep 1  # the runs are named by the second
}
last_run() { ls -d "$t"/nightly/runs/* | tail -1; }
has() { grep -qF -- "$2" "$1" || fail "$1 lacks '$2'"; }
lacks() { ! grep -qF -- "$2" "$1" || fail "$1 says '$2'"; }

experiment 60
night
[ "$rc" = 0 ] || { cat "$t/night.log"; fail "night 1 exit $rc, not 0"; }
run1=$(last_run)
has "$run1/audit/audit.md" "# renderaudit audit: BASELINE ESTABLISHED: NOTHING COMPARED"
has "$run1/audit/audit.md" "| baseline recorded |"
for word in UNCHANGED unchanged "No test is significant" "same on both sides"; do
  lacks "$run1/audit/audit.md" "$word"
done
# "compared" only in "nothing compared"
[ "$(grep -o compared "$run1/audit/audit.md" | wc -l)" = \
  "$(grep -o "nothing compared" "$run1/audit/audit.md" | wc -l)" ] \
  || fail "$run1/audit/audit.md reads as a comparison: $(grep -n compared "$run1/audit/audit.md")"
cases=$(grep -c "<testcase " "$run1/audit/junit.xml" || true)
skipped=$(grep -c '<skipped message="baseline established: nothing compared"/>' "$run1/audit/junit.xml" || true)
[ "$cases" = "$skipped" ] || fail "junit.xml: $skipped of $cases cases skipped, not all"
lacks "$run1/audit/junit.xml" "<failure"
has "$run1/report/report.html" "baseline established: nothing compared"
lacks "$run1/report/report.html" "PASS"
has "$t/night.log" "audit: baseline established: $run1 is the baseline"
has "$t/night.log" "history: the baseline recorded in $t/nightly/history.sqlite"
has "$t/night.log" "nightly: BASELINE RECORDED (exit 0) in "
for word in "primitives changed" "significant" "unchanged" "nothing appended"; do
  lacks "$t/night.log" "$word"
done
[ "$(wc -l < "$t/night.log")" -le 8 ] || { cat "$t/night.log"; fail "night 1 printed more than 8 lines"; }

night
[ "$rc" = 0 ] || { cat "$t/night.log"; fail "night 2 exit $rc, not 0"; }
run2=$(last_run)
has "$run2/audit/audit.md" "# renderaudit audit: UNCHANGED"
has "$run2/report/report.html" "PASS"
has "$t/night.log" "audit: unchanged: 0 of "
has "$t/night.log" "nightly: UNCHANGED (exit 0) in "
has "$t/night.log" "history: $t/nightly/history.txt"
for word in "| platform |" "trend figures" "wrote "; do
  lacks "$t/night.log" "$word"
done
[ "$(wc -l < "$t/night.log")" -le 8 ] || { cat "$t/night.log"; fail "night 2 printed more than 8 lines"; }
"$build/renderaudit" history --db "$t/nightly/history.sqlite" > "$t/history.txt"
has "$t/history.txt" "history.sqlite: 2 audits,"
has "$t/history.txt" " baseline "
has "$t/history.txt" "nothing (baseline recorded)"
has "$t/history.txt" " unchanged "
has "$t/nightly/history.txt" "history.sqlite: 2 audits,"

experiment 70
night
[ "$rc" = 2 ] || { cat "$t/night.log"; fail "night 3 (edited experiment) exit $rc, not 2"; }
run3=$(last_run)
has "$t/night.log" "not runs of the same experiment"
has "$t/night.log" "- points = 60"
has "$t/night.log" "+ points = 70"
has "$t/night.log" "scripts/nightly.sh --promote $run3"
promotes=$(grep -c -- "--promote" "$t/night.log" || true)
[ "$promotes" = 1 ] || { cat "$t/night.log"; fail "night 3 says the --promote command $promotes times, not once"; }
lacks "$t/night.log" "verdict in"
[ ! -e "$run3/audit/audit.md" ] || fail "night 3 wrote an audit.md"
has "$run3/report/report.html" "no verdict"
has "$run3/report/report.html" "not runs of the same experiment"

(cd "$here" && NIGHTLY_DIR="$t/nightly" scripts/nightly.sh --promote "$run3") > /dev/null
night
[ "$rc" = 0 ] || { cat "$t/night.log"; fail "night 4 (after --promote) exit $rc, not 0"; }
has "$(last_run)/audit/audit.md" "# renderaudit audit: UNCHANGED"
echo "nightly-test: four nights as documented"
