#!/usr/bin/env bash
# `renderaudit bisect --ways 3 --slurm` on a real Slurm (one machine, scripts/slurm-local.sh;
# ctest bisect_slurm), with the stand-in builds of tests/scripts/bisect-fixture.sh:
#   1. one culprit in 64 commits: each round a job array of 3 builds, the culprit named in at most
#      3 rounds, as --ways 3 names it here;
#   2. a build that fails inside a round: its task submitted again once, then counted as failed,
#      the change next to it left with candidates (exit 1); no worktree left behind;
#   3. a task cancelled under its build (as when its node dies): submitted again, the culprit named.
# Usage: tests/scripts/bisect-slurm-test.sh BUILD_DIR. Exit 0 pass, 1 fail, 77 when no Slurm cluster
# could be started here (not root, no packages): the test is then skipped, loudly.
. "$(dirname "$0")/test-common.sh"
state=${RENDERAUDIT_SLURM_STATE:-/tmp/renderaudit-slurm-bisect-test}
export SLURM_CONF=$state/slurm.conf
export PATH=$PATH:/usr/sbin
if ! "$root/scripts/slurm-local.sh" start "$state"; then
  echo "bisect-slurm-test: SKIPPED: no Slurm cluster could be started on this machine" >&2
  exit 77
fi
on_exit='"$root/scripts/slurm-local.sh" stop "$state" >/dev/null 2>&1'
. "$(dirname "$0")/bisect-fixture.sh"
make_run

bisect() {  # bisect NAME SOURCE GOOD BAD [options]: exit code in $rc
  local name=$1 src=$2 good=$3 bad=$4
  shift 4
  set +e
  "$ra" bisect "$t/run" --between faulty@good faulty@bad --source "$src" --good "$good" \
    --bad "$bad" --build-command "$cmd" --out "$t/$name" --jobs 1 --max-primitives 6 \
    --no-pictures --ways 3 "$@" >"$t/$name.out" 2>"$t/$name.err"
  rc=$?
  set -e
}
culprits() { grep '^first bad commit: ' "$t/$1.out" | cut -d' ' -f5- | tr '\n' ';'; }
no_worktrees() {
  [ "$(git -C "$1" worktree list | wc -l)" = 1 ] || { git -C "$1" worktree list; fail "worktrees left in $1"; }
}

# 1. One culprit (c33) in 64 commits.
words=()
for i in $(seq 0 64); do if [ "$i" -lt 33 ]; then words+=(good); else words+=(bad); fi; done
h="$t/h64"
make_history "$h" "${words[@]}"
t0=$(date +%s.%N)
bisect s3 "$h" "$(c "$h" 0)" "$(c "$h" 64)" --slurm --allow-node-local
[ $rc -eq 0 ] || { cat "$t/s3.err"; fail "--slurm exited $rc"; }
[ "$(culprits s3)" = "c33: bad (6 primitives);" ] || { cat "$t/s3.err"; fail "--slurm named $(culprits s3)"; }
rounds=$(grep -c '^bisect: round [0-9]*: [0-9]* builds* (' "$t/s3.err")
[ "$rounds" -le 3 ] || fail "$rounds rounds"
grep -q '^bisect: round 1: 3 builds submitted as Slurm array job [0-9]*$' "$t/s3.err" ||
  { cat "$t/s3.err"; fail "no job array said"; }
grep -q '^bisect: round 1 on Slurm: ' "$t/s3.err" || fail "the round's state was not said"
no_worktrees "$h"
echo "bisect-slurm-test: one culprit in 64 commits named in $rounds rounds of Slurm job arrays" \
  "($(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.0f", b - a }') s)"

# 2. A failed build in a round: c0-c7 good, c8 broken, c9-c16 bad; round 1 builds c4, c8, c12.
words=()
for i in $(seq 0 16); do if [ "$i" -lt 8 ]; then words+=(good); elif [ "$i" = 8 ]; then words+=(broken); else words+=(bad); fi; done
h3="$t/h3"
make_history "$h3" "${words[@]}"
bisect f3 "$h3" "$(c "$h3" 0)" "$(c "$h3" 16)" --slurm --allow-node-local
[ $rc -eq 1 ] || { cat "$t/f3.err"; fail "a failed build next to the change: exit $rc, not 1"; }
grep -q "^bisect: round 1: build 2 failed (the task exited with status 2); submitting it again$" "$t/f3.err" ||
  { cat "$t/f3.err"; fail "the failed task was not submitted again"; }
grep -q "skipped $(c "$h3" 8 | cut -c1-12) for every primitive: build failed: builds build: the build command step failed" "$t/f3.err" ||
  { cat "$t/f3.err"; fail "the failed build is not named"; }
[ "$(grep -c "^unattributed: .* (one of: $(c "$h3" 8 | cut -c1-12) $(c "$h3" 9 | cut -c1-12))" "$t/f3.out")" = 6 ] ||
  { cat "$t/f3.out"; fail "candidates"; }
no_worktrees "$h3"

# 3. A task killed mid-build (scancel: what a node failure looks like from here): run again.
h4="$t/h4"
make_history "$h4" "${words[@]//broken/good}"
ends=" $(c "$h4" 0) $(c "$h4" 16) "
cmd='case "'"$ends"'" in *" $RENDERAUDIT_SOURCE_COMMIT "*) ;; *) [ -e '"$t"'/killed ] || sleep 20;; esac; '"$cmd"
bisect k3 "$h4" "$(c "$h4" 0)" "$(c "$h4" 16)" --slurm --allow-node-local &
victim=$!
pids+=("$victim")
for _ in $(seq 600); do
  job=$(sed -n 's/^bisect: round 1: 3 builds submitted as Slurm array job \([0-9]*\)$/\1/p' "$t/k3.err" 2>/dev/null || true)
  [ -n "$job" ] && [ "$(squeue -h -r -j "${job}_2" -o %T 2>/dev/null)" = RUNNING ] && break
  sleep 0.2
done
[ -n "$job" ] || { cat "$t/k3.err"; fail "round 1 was not submitted"; }
sleep 2
scancel "${job}_2"
touch "$t/killed"
wait "$victim" || true
grep -q "^bisect: round 1: build 2 failed (the task left the queue without an exit status" "$t/k3.err" ||
  { cat "$t/k3.err"; fail "the killed task was not noticed"; }
[ "$(culprits k3)" = "c9: bad (6 primitives);" ] || { cat "$t/k3.err"; fail "after a killed task: $(culprits k3)"; }
no_worktrees "$h4"
echo "bisect-slurm-test: PASS"
