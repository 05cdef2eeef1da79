#!/usr/bin/env bash
# The nightly driver audit: run the experiment into a dated directory, audit it against the
# baseline run (promoting tonight's run if there is none yet), append the verdict to the history
# database, and write tonight's report. Exit code: the audit's (0 unchanged, 1 changed, 2 failed).
#
#   scripts/nightly.sh                       # what `make nightly` runs
#   scripts/nightly.sh --promote RUN_DIR     # make RUN_DIR the baseline from now on
#
# Settings (environment): NIGHTLY_EXPERIMENT (experiments/nightly.toml), NIGHTLY_DIR
# (outputs/nightly), BUILD (build), JOBS (nproc), EXPECT_RENDERER (a GL_RENDERER regex, optional),
# NIGHTLY_SPEED: `on` (default: drawing time judged too, a slower group makes the night
# CHANGED), `warn` (judged, a slower group only reported), `off`.
set -euo pipefail

experiment=${NIGHTLY_EXPERIMENT:-experiments/nightly.toml}
root=${NIGHTLY_DIR:-outputs/nightly}
bin=${BUILD:-build}/renderaudit
jobs=${JOBS:-$(nproc)}
baseline="$root/baseline"  # a symbolic link to the baseline run directory
db="$root/history.sqlite"

if [[ ${1:-} == --promote ]]; then
  run=${2:?usage: scripts/nightly.sh --promote RUN_DIR}
  [[ -f $run/manifest.json ]] || { echo "nightly: $run is not a run directory" >&2; exit 2; }
  mkdir -p "$root"
  ln -sfn "$(realpath "$run")" "$baseline"
  echo "nightly: baseline is now $(realpath "$run")"
  exit 0
fi

started=$(date +%s)
tonight="$root/runs/$(date -u +%Y-%m-%dT%H%M%SZ)"
mkdir -p "$root/runs"
expect=()
[[ -n ${EXPECT_RENDERER:-} ]] && expect=(--expect-renderer "$EXPECT_RENDERER")
case ${NIGHTLY_SPEED:-on} in
  on) speed=(--speed) ;;
  warn) speed=(--speed --speed-warn-only) ;;
  off) speed=() ;;
  *) echo "nightly: NIGHTLY_SPEED='$NIGHTLY_SPEED' (allowed: on, warn, off)" >&2; exit 2 ;;
esac

# Each step prints a line or two; the tables stay in their files (summary.md, audit/audit.md,
# history.txt), and the last line says what the night found, where, and how long it took.
status=0
"$bin" run "$experiment" --out "$tonight" --jobs "$jobs" --brief "${expect[@]}" || status=$?
if (( status == 2 || status == 130 )); then
  echo "nightly: the run did not complete (exit $status); see $tonight" >&2
  exit 2
fi

# The first night audits its run against itself: the audit says "baseline established: nothing
# compared" (exit 0) in audit.md, the report and junit.xml (every case skipped), and the history
# records the night with the verdict "baseline".
if [[ ! -e $baseline ]]; then
  ln -sfn "$(realpath "$tonight")" "$baseline"
fi

verdict=0
"$bin" audit "$(realpath "$baseline")" "$tonight" --db "$db" --brief "${speed[@]}" \
  2> "$tonight/audit.stderr" || verdict=$?
cat "$tonight/audit.stderr" >&2
refused=0
if [[ -f $tonight/audit/audit.json ]]; then
  rm -f "$tonight/audit.stderr"
else
  # The audit refused its input (another experiment, a damaged run): no verdict tonight. The
  # report says why, from audit/refused.txt.
  refused=1
  mkdir -p "$tonight/audit"
  mv "$tonight/audit.stderr" "$tonight/audit/refused.txt"
  # The audit's message above says how to promote tonight's run where that is the remedy (an
  # experiment changed on purpose); it is not said twice.
  echo "nightly: no verdict tonight: the audit refused to compare $tonight with the baseline" \
       "$(realpath "$baseline") (above)." >&2
fi
"$bin" analyze "$tonight" >/dev/null
"$bin" plot "$tonight" >/dev/null
if ! reported=$("$bin" report "$tonight" 2>&1); then
  echo "$reported" >&2
  echo "nightly: the report of $tonight failed (above)" >&2
  exit 2
fi
grep '^finding: ' <<<"$reported" || true
# The recent history and its trend figures, into files: history.txt beside the database.
history=""
if [[ -f $db ]] && "$bin" history --db "$db" --last 14 > "$root/history.txt" 2>&1; then
  history="; history: $root/history.txt"
fi

# How long the night took, in the words of the program's summaries (util::elapsed_text) in whole
# seconds: the script times the commands it runs, so it spells the time itself rather than ask a
# binary that may be the thing that failed.
took=$(( $(date +%s) - started ))
if (( took >= 3600 )); then took=$(printf '%d h %02d min' $((took / 3600)) $((took / 60 % 60)))
elif (( took >= 60 )); then took="$((took / 60)) min $((took % 60)) s"
else took="$took s"; fi
report="report: $tonight/report/report.pdf"
if (( refused )); then
  echo "nightly: NO VERDICT (exit 2) in $took: the audit refused to compare; $report$history"
elif (( verdict == 0 )) && [[ "$(realpath "$baseline")" == "$(realpath "$tonight")" ]]; then
  echo "nightly: BASELINE RECORDED (exit $verdict) in $took: tonight's run is the baseline later" \
       "nights are audited against: $(realpath "$tonight"); $report$history"
else
  names=(UNCHANGED CHANGED FAILED)
  echo "nightly: ${names[verdict]:-FAILED} (exit $verdict) in $took: $tonight/audit/audit.md;" \
       "$report$history"
fi
exit "$verdict"
