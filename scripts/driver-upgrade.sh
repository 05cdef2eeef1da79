#!/usr/bin/env bash
# `make driver-upgrade`: the installed Mesa against the newest Mesa of Debian's bookworm-backports,
# end to end: fetch the driver build into the build cache (renderaudit builds fetch), run
# experiments/driver-upgrade.toml (nist2008 views; osmesa-* and egl-*, llvmpipe and softpipe, each
# on the installed Mesa and on the driver build), audit every pair with `audit RUN --between P
# P@backports` (pixels, and drawing time: both sides drawn again, --speed), and write one report,
# OUT/upgrade-report.pdf and .html (set by `renderaudit report --markdown` from the Markdown beside
# them), that opens with one sentence of what changed per driver and one of what got faster or
# slower (made from the counts and the time verdicts by `renderaudit report --upgrade-sentences`)
# and the worst primitive before and after, then what changed per back end, kind and view group.
# The pairs audited are the experiment's platforms P drawn also as P@backports. About 10 minutes
# on 2 cores for the pixels; timing the drawing adds, on the same 2 cores under load, about 35 s
# per llvmpipe pair and 2.5 min per softpipe pair (softpipe draws the 907 x 907 views slowly):
# about 6 minutes for the four pairs (docs/driver-builds.md).
#
# Usage: scripts/driver-upgrade.sh [PROGRAM_DIR] [--smoke]   (MIRROR=URL: another Debian archive)
#   PROGRAM_DIR: the program's build folder, where CMake built renderaudit (default: build). A
#   driver build is a Mesa in the build cache (renderaudit builds), named P@BUILD in the experiment.
#   MESA_SOURCE=DIR [MESA_REF=REF]: also a driver build of that Mesa source tree (renderaudit builds
#   build; scripts/install-mesa-build-deps.sh first), drawn through EGL as egl-*@source and
#   audited against the installed Mesa, so the report covers three versions side by side.
#   UPGRADE_SPEED: `on` (default: each audit also judges drawing time with --speed-warn-only, so a
#   slower driver is reported, in its audit's line and on page 1, but changes no exit code and no
#   count of changed audits; the audit's defaults, 10 rounds of 100 primitives per kind and view),
#   `off` (pixels only).
#   --smoke: 40 primitives per kind and view into PROGRAM_DIR/driver-upgrade-smoke, drawing time
#   in 3 rounds (about 1 minute for the four pairs), and a driver build already in the cache is
#   used as is (the test suite's run of this script).
# Exit 0: every audit ran (whatever it found); 2: a step failed or UPGRADE_SPEED is neither on nor
# off; 77: the Debian registry cannot be reached and no driver build is cached (the test suite then
# skips, loudly).
set -uo pipefail

program_dir=${1:-build}
smoke=0
[ "${2:-}" = --smoke ] && smoke=1
repo=$(cd "$(dirname "$0")/.." && pwd)
ra=$(cd "$program_dir" && pwd)/renderaudit
suite=bookworm-backports
experiment=${EXPERIMENT:-$repo/experiments/driver-upgrade.toml}
out=${OUT:-$repo/outputs/driver-upgrade}

say() { echo "driver-upgrade: $*"; }
started=$(date +%s)
step() { say "step $1 of 4 ($(( ($(date +%s) - started) / 60 )) min so far): $2"; }
die() { echo "driver-upgrade: $*" >&2; exit 2; }
[ -x "$ra" ] || die "$ra is not built (make build)"
# Drawing time judged by each audit (a slower group a warning: the audits' exit codes, and so this
# script's counts, stay those of the pixels); the smoke run's fewer rounds only exercise it.
case ${UPGRADE_SPEED:-on} in
  on) speed=(--speed --speed-warn-only) rounds=10
      if [ $smoke = 1 ]; then speed+=(--speed-repeats 3) rounds=3; fi ;;
  off) speed=() ;;
  *) die "UPGRADE_SPEED='$UPGRADE_SPEED' (allowed: on, off)" ;;
esac

if [ $smoke = 1 ]; then
  out=$(cd "$program_dir" && pwd)/driver-upgrade-smoke
  rm -rf "$out"
  mkdir -p "$out"
  sed -e 's/^name = .*/name = "driver-upgrade-smoke"/' \
      -e 's/^\(points\|lines\|triangles\) = [0-9]*/\1 = 40/' \
      -e 's/^shard_size = .*/shard_size = 40/' "$experiment" > "$out.toml"
  experiment=$out.toml
fi

# 1. The driver build: fetched (always for the real audit: the suite's newest), or the cached one.
if [ $smoke = 1 ] && listed=$("$ra" builds list) && grep -q "suite $suite" <<<"$listed"; then
  say "using the cached build of $suite"
else
  step 1 "fetching the Mesa of $suite (apt-get download through a private apt configuration)"
  if ! fetched=$("$ra" builds fetch "$suite" ${MIRROR:+--mirror "$MIRROR"} 2>&1); then
    echo "$fetched" >&2
    if grep -q "unreachable" <<<"$fetched"; then
      echo "driver-upgrade: SKIPPED: the Debian registry (${MIRROR:-deb.debian.org}) cannot be reached from" \
           "here, and no build of $suite is cached; nothing was run" >&2
      exit 77
    fi
    die "the fetch failed (above)"
  fi
  # the driver build's name and versions; its file list goes to a file
  mkdir -p "$(dirname "$out")"
  echo "$fetched" > "$out.fetch.txt"
  say "fetched $(sed -n 1p <<<"$fetched"); its files: $out.fetch.txt"
fi

# 1b. A driver build of a Mesa source tree (optional): its EGL platforms join the experiment.
if [ -n "${MESA_SOURCE:-}" ]; then
  say "building Mesa from $MESA_SOURCE${MESA_REF:+ at $MESA_REF} (renderaudit builds build; a cold build takes about 10 minutes on 2 cores)"
  built=$("$ra" builds build "$MESA_SOURCE" ${MESA_REF:+--ref "$MESA_REF"}) || die "the source build failed (above)"
  echo "$built"
  source_dir=$(sed -n 's/^  folder: //p' <<<"$built" | sed -n 1p)
  [ -n "$source_dir" ] || die "the source build did not say its folder"
  mkdir -p "$out"
  sed -e 's/^platforms = \[/platforms = ["egl-llvmpipe@source", "egl-softpipe@source",\n             /' \
      "$experiment" > "$out.with-source.toml"
  # The source path and the ref are the user's: escaped, never pasted into TOML as they are.
  /usr/bin/python3 "$repo/scripts/build_table.py" source "$source_dir" \
    "renderaudit builds build $MESA_SOURCE${MESA_REF:+ --ref $MESA_REF}" >> "$out.with-source.toml"
  experiment=$out.with-source.toml
fi

# 2. The run, with its progress (on a terminal a line rewritten; in a log a line now and then).
step 2 "running $experiment into $out (resumable: the same command again goes on)"
ran=$("$ra" run "$experiment" --out "$out" --brief) || { echo "$ran"; die "the run failed (above); run the same command again to resume"; }
echo "$ran"
primitives=$(sed -n 's/^run: .*: \([0-9,]*\) primitives in .*/\1/p' <<<"$ran")

# 3. The audits: PLATFORM against PLATFORM@DRIVER_BUILD; `audited` (backports) and
# `source_audited` list those that ran.
status=0
audit_driver_build() {  # DRIVER_BUILD PLATFORM...
  local driver_build=$1 p dir rc suffix
  shift
  # the folder the report is told of (report --audit-suffix) for a driver build other than
  # backports
  suffix=$([ "$driver_build" = backports ] || echo "-$driver_build")
  for p in "$@"; do
    dir=$out/audit-$p$suffix
    # its verdict on stdout (the first line: what changed, every faster or slower group among the
    # reasons); the timing's progress and any error on stderr, kept apart
    "$ra" audit "$out" --between "$p" "$p@$driver_build" --no-history "${speed[@]}" --out "$dir" \
      > "$dir.log" 2> "$dir.stderr.log"
    rc=$?
    [ $rc = 1 ] && changed+=("$p@$driver_build")
    if [ $rc -gt 1 ]; then
      cat "$dir.log" "$dir.stderr.log" >&2
      say "audit of $p against $p@$driver_build failed (exit $rc)"
      status=2
    else
      say "audit of $p against $p@$driver_build: $(head -1 "$dir.log")"
      [ "$driver_build" = backports ] && audited+=("$p") || source_audited+=("$p")
    fi
  done
}
# The platforms P of the experiment that it also draws as P@DRIVER_BUILD.
pairs_of() {  # DRIVER_BUILD
  /usr/bin/python3 -c 'import sys, tomllib
ps = tomllib.load(open(sys.argv[1], "rb")).get("platforms", [])
print(" ".join(p for p in ps if "@" not in p and p + "@" + sys.argv[2] in ps))' "$experiment" "$1"
}
audited=()
source_audited=()
changed=()
step 3 "auditing each platform against its build$([ ${#speed[@]} = 0 ] ||
  echo ", timing the drawing too ($rounds rounds per pair: under a minute for llvmpipe, longer" \
       "for softpipe; UPGRADE_SPEED=off: pixels only)")"
backports_pairs=$(pairs_of backports) || die "cannot read the platforms of $experiment"
[ -n "$backports_pairs" ] || die "$experiment draws no platform P beside P@backports: nothing to audit"
# shellcheck disable=SC2086  # one word per platform
audit_driver_build backports $backports_pairs
if [ -n "${MESA_SOURCE:-}" ]; then
  # shellcheck disable=SC2086
  audit_driver_build source $(pairs_of source)
fi

# 4. The report (`renderaudit report --upgrade`, triage/upgrade_report.h): the first sentence says
# what changed per driver, the worst primitive of each distinct finding before and after, a table
# of contents, what changed per back end, kind and view group (the audits' comparison), then each
# audit's own report.
report=$out/upgrade-report.md
step 4 "writing the report"
if [ ${#audited[@]} -gt 0 ]; then
  "$ra" report "$out" --upgrade backports --platforms "${audited[@]}" > "$report" ||
    die "the report failed (above)"
  for p in "${audited[@]}"; do
    { echo; echo "# Audit of $p"; echo; sed -e 's/^## /### /' -e 's/^# /## /' "$out/audit-$p/audit.md"; } >> "$report"
  done
  if [ ${#source_audited[@]} -gt 0 ]; then
    { echo; echo "# The installed Mesa against Mesa built from source ($MESA_SOURCE${MESA_REF:+ at $MESA_REF})"; echo
      "$ra" report "$out" --upgrade source --audit-suffix -source --platforms "${source_audited[@]}" |
        sed -e '/^\[TOC\]$/d' -e 's/^## /### /' -e 's/^# /## /'
    } >> "$report" || die "the report of the source build failed (above)"
  fi
  # the Markdown set as PDF and HTML, its pictures in the pages, like the run reports
  "$ra" report --markdown "$report" > "$out/upgrade-report.log" 2>&1 ||
    { cat "$out/upgrade-report.log" >&2; die "setting the report as PDF failed (above)"; }
  say "report: ${report%.md}.pdf (and .html; the Markdown: $report)"
fi

# The last line: what was found, how big the run was, how long it all took.
took=$(( $(date +%s) - started ))
n_audits=$(( ${#audited[@]} + ${#source_audited[@]} ))
found="${#changed[@]} of $n_audits audits changed${changed[*]:+ (${changed[*]})}"
[ $status = 0 ] || found="$found; an audit FAILED (above)"
say "done in $((took / 60)) min $((took % 60)) s: ${primitives:-?} primitives, $found;" \
    "report: $([ ${#audited[@]} -gt 0 ] && echo "${report%.md}.pdf" || echo "none")"
exit $status
