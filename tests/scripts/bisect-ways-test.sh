#!/usr/bin/env bash
# `renderaudit bisect --ways K` end to end with real drawing and no compiler (ctest bisect_ways):
# stand-in driver builds and git histories (tests/scripts/bisect-fixture.sh). Checked: one culprit in 64
# commits named in at most 3 rounds with --ways 3 (6 with --ways 1), the round lines and records;
# the same culprits with --ways 1 and --ways 3 on a history of several changes; two culprits; a
# failed build inside a round (next to the change: candidates, exit 1); a round interrupted with
# SIGINT (exit 130, its builds stopped, every worktree removed, the tree where it was) and
# resumed by the same command; a round killed with -9, its worktrees removed by the next bisection
# (with --ways 1: the ways may change on resume).
# Usage: tests/scripts/bisect-ways-test.sh BUILD_DIR
. "$(dirname "$0")/test-common.sh"
. "$(dirname "$0")/bisect-fixture.sh"
make_run

bisect() {  # bisect NAME SOURCE GOOD BAD [options]: exit code in $rc
  local name=$1 src=$2 good=$3 bad=$4
  shift 4
  set +e
  "$ra" bisect "$t/run" --between faulty@good faulty@bad --source "$src" --good "$good" \
    --bad "$bad" --build-command "$cmd" --out "$t/$name" --jobs 2 --max-primitives 6 \
    --no-pictures "$@" >"$t/$name.out" 2>"$t/$name.err"
  rc=$?
  set -e
}
culprits() { grep '^first bad commit: ' "$t/$1.out" | cut -d' ' -f5- | tr '\n' ';'; }
rounds_of() { grep -c '^bisect: round [0-9]*: ' "$t/$1.err" || true; }
no_worktrees() {  # SOURCE: only the tree itself is a worktree, no slot left
  [ "$(git -C "$1" worktree list | wc -l)" = 1 ] || { git -C "$1" worktree list; fail "worktrees left in $1"; }
  local slots
  slots=$(ls "$1/.git/renderaudit-bisect" 2>/dev/null || true)
  ! grep -q '^slot-' <<<"$slots" || fail "slot folders left in $1"
}

# 1. One culprit in 64 commits (c33): --ways 1 takes 6 rounds of one build, --ways 3 at most 3.
words=()
for i in $(seq 0 64); do if [ "$i" -lt 33 ]; then words+=(good); else words+=(bad); fi; done
h="$t/h64"
make_history "$h" "${words[@]}"
bisect w1 "$h" "$(c "$h" 0)" "$(c "$h" 64)" --ways 1
[ $rc -eq 0 ] || { cat "$t/w1.err"; fail "--ways 1 exited $rc"; }
bisect w3 "$h" "$(c "$h" 0)" "$(c "$h" 64)" --ways 3
[ $rc -eq 0 ] || { cat "$t/w3.err"; fail "--ways 3 exited $rc"; }
[ "$(culprits w1)" = "c33: bad (6 primitives);" ] || fail "--ways 1: $(culprits w1)"
[ "$(culprits w3)" = "$(culprits w1)" ] || fail "--ways 3 named $(culprits w3)"
[ "$(rounds_of w1)" = 6 ] || { cat "$t/w1.err"; fail "--ways 1 took $(rounds_of w1) rounds, not 6"; }
[ "$(rounds_of w3)" -le 3 ] || { cat "$t/w3.err"; fail "--ways 3 took $(rounds_of w3) rounds"; }
grep -q '^bisect: round 1: 1 build ([0-9a-f]\{12\}), 6 changes unresolved, about 6 rounds to go$' "$t/w1.err" ||
  { cat "$t/w1.err"; fail "the --ways 1 round line"; }
grep -q '^bisect: round 1: 3 builds ([0-9a-f]\{12\} [0-9a-f]\{12\} [0-9a-f]\{12\}), 6 changes unresolved, about 3 rounds to go$' "$t/w3.err" ||
  { cat "$t/w3.err"; fail "the --ways 3 round line"; }
grep -q '^bisect: 6 rounds, 6 builds, .* of building$' "$t/w1.err" || fail "--ways 1 summary line"
grep -q '^bisect: [23] rounds, [0-9]* builds, .* of building$' "$t/w3.err" || { cat "$t/w3.err"; fail "--ways 3 summary line"; }
/usr/bin/python3 - "$t/w3/bisect.json" "$t/w1/bisect.json" <<'PY' || fail "bisect.json rounds"
import json, sys
w3, w1 = (json.load(open(p)) for p in sys.argv[1:3])
assert all(r["ways"] == 1 and r["where"] == "tree" and len(r["commits"]) == 1 for r in w1["rounds"]), w1["rounds"]
assert len(w1["rounds"]) == len(w1["steps"]) == 6
r = w3["rounds"]
assert 2 <= len(r) <= 3 and all(x["ways"] == 3 and x["where"] == "worktrees" and x["finished"] for x in r), r
assert len(r[0]["commits"]) == 3 and r[0]["unresolved"] == 6 and r[0]["rounds_to_go"] == 3, r[0]
built = [s["commit"] for s in w3["steps"]]
assert len(built) == len(set(built)), built
cancelled = sum(len(x["cancelled"]) for x in r)
assert len(built) + cancelled == sum(len(x["commits"]) for x in r), (built, r)
PY
grep -q "| round | builds | where |" "$t/w3/bisect.md" || fail "bisect.md has no rounds table"
no_worktrees "$h"
[ "$(git -C "$h" symbolic-ref --short HEAD)" = main ] || fail "the tree left its branch"
echo "bisect-ways-test: one culprit in 64 commits: $(rounds_of w1) rounds with --ways 1, $(rounds_of w3) with --ways 3"

# 2. Several changes (the even lines at c4, the odd ones at c4, c5 and c6): the same culprits.
g="$t/mesa"
make_history "$g" good good good good bad neither bad bad
bisect m1 "$g" "$(c "$g" 0)" "$(c "$g" 7)" --ways 1
bisect m3 "$g" "$(c "$g" 0)" "$(c "$g" 7)" --ways 3
[ $rc -eq 0 ] && [ "$(culprits m1)" = "c4: bad (6 primitives);c5: neither (3 primitives);c6: bad (3 primitives);" ] &&
  [ "$(culprits m3)" = "$(culprits m1)" ] || { cat "$t/m3.err"; fail "several changes: '$(culprits m1)' and '$(culprits m3)'"; }

# 3. Two culprits of disjoint primitives: the even lines at c10, the odd ones at c20.
words=()
for i in $(seq 0 24); do if [ "$i" -lt 10 ]; then words+=(good); elif [ "$i" -lt 20 ]; then words+=(neither); else words+=(bad); fi; done
h2="$t/h2"
make_history "$h2" "${words[@]}"
bisect t3 "$h2" "$(c "$h2" 0)" "$(c "$h2" 24)" --ways 3
[ $rc -eq 0 ] && [ "$(culprits t3)" = "c10: neither (3 primitives);c20: bad (3 primitives);" ] ||
  { cat "$t/t3.err"; fail "two culprits: $(culprits t3)"; }

# 4. A failed build inside a round, next to the change: c0-c7 good, c8 broken, c9-c16 bad.
words=()
for i in $(seq 0 16); do if [ "$i" -lt 8 ]; then words+=(good); elif [ "$i" = 8 ]; then words+=(broken); else words+=(bad); fi; done
h3="$t/h3"
make_history "$h3" "${words[@]}"
bisect f3 "$h3" "$(c "$h3" 0)" "$(c "$h3" 16)" --ways 3
[ $rc -eq 1 ] || { cat "$t/f3.err"; fail "a failed build next to the change: exit $rc, not 1"; }
grep -q "skipped $(c "$h3" 8 | cut -c1-12) for every primitive: build failed: builds build: the build command step failed" "$t/f3.err" &&
  grep -q "^cannot build broken" "$t/f3.err" || { cat "$t/f3.err"; fail "the failed build is not named"; }
[ "$(grep -c "^unattributed: .* (one of: $(c "$h3" 8 | cut -c1-12) $(c "$h3" 9 | cut -c1-12))" "$t/f3.out")" = 6 ] ||
  { cat "$t/f3.out"; fail "candidates"; }
/usr/bin/python3 - "$t/f3/bisect.json" "$(c "$h3" 8)" <<'PY' || fail "the round does not record the failed build"
import json, sys
j = json.load(open(sys.argv[1]))
assert any(sys.argv[2] in r["failed"] for r in j["rounds"]), j["rounds"]
PY
no_worktrees "$h3"

# 5. SIGINT during a round: its three builds stopped, the worktrees removed, the tree where it
# was, exit 130; the same command resumes. The steps' builds sleep while RA_WAYS_SLOW is set.
h4="$t/h4"
make_history "$h4" "${words[@]//broken/good}"
git -C "$h4" checkout -q -b topic
ends="$(c "$h4" 0) $(c "$h4" 16)"
cmd='case " '"$ends"' " in *" $RENDERAUDIT_SOURCE_COMMIT "*) ;; *) [ -z "${RA_WAYS_SLOW:-}" ] || sleep 29.3;; esac; '"$cmd"
RA_WAYS_SLOW=1 "$ra" bisect "$t/run" --between faulty@good faulty@bad --source "$h4" --good "$(c "$h4" 0)" \
  --bad "$(c "$h4" 16)" --build-command "$cmd" --out "$t/int" --jobs 2 --max-primitives 6 \
  --no-pictures --ways 3 >"$t/int.out" 2>"$t/int.err" &
victim=$!
pids+=("$victim")
for _ in $(seq 1200); do [ "$(grep -c '^bisect:   building .* in /' "$t/int.err" 2>/dev/null)" = 3 ] && break; sleep 0.1; done
[ "$(grep -c '^bisect:   building .* in /' "$t/int.err")" = 3 ] || { cat "$t/int.err"; fail "the round's three builds did not start"; }
sleep 1
[ "$(git -C "$h4" worktree list | wc -l)" = 4 ] || { git -C "$h4" worktree list; fail "three worktrees expected during the round"; }
kill -INT "$victim"
set +e
wait "$victim"
rc=$?
set -e
[ $rc = 130 ] || { cat "$t/int.err"; fail "SIGINT: exit $rc, not 130"; }
grep -q "interrupted by SIGINT: the tree is back where it was; the same command resumes" "$t/int.err" || fail "not said"
for _ in $(seq 50); do pgrep -f "^sleep 29\.3" >/dev/null || break; sleep 0.1; done
! pgrep -f "^sleep 29\.3" >/dev/null || { ps -o pid,ppid,pgid,stat,cmd -p "$(pgrep -d, -f "^sleep 29\.3")"; fail "a build of the round was left running"; }
no_worktrees "$h4"
[ "$(git -C "$h4" symbolic-ref --short HEAD)" = topic ] || fail "the tree is not back on its branch"
/usr/bin/python3 - "$t/int/bisect.json" <<'PY' || fail "the interrupted round's record"
import json, sys
j = json.load(open(sys.argv[1]))
assert len(j["rounds"]) == 1 and not j["rounds"][0]["finished"] and not j["steps"], (j["rounds"], j["steps"])
PY
"$ra" bisect "$t/run" --between faulty@good faulty@bad --source "$h4" --good "$(c "$h4" 0)" \
  --bad "$(c "$h4" 16)" --build-command "$cmd" --out "$t/int" --jobs 2 --max-primitives 6 \
  --no-pictures --ways 3 >"$t/int2.out" 2>"$t/int2.err" || { cat "$t/int2.err"; fail "the resumed bisection"; }
grep -q "resuming .*: 0 steps built" "$t/int2.err" || { cat "$t/int2.err"; fail "did not resume"; }
[ "$(culprits int2)" = "c9: bad (6 primitives);" ] || fail "resumed: $(culprits int2)"
no_worktrees "$h4"
[ "$(git -C "$h4" symbolic-ref --short HEAD)" = topic ] || fail "the resumed bisection moved the tree"
# kill -9 during a round leaves its worktrees; the next bisection of the tree removes them and the
# same command resumes.
export RENDERAUDIT_BUILD_CACHE="$t/cache-kill"
RA_WAYS_SLOW=1 "$ra" bisect "$t/run" --between faulty@good faulty@bad --source "$h4" --good "$(c "$h4" 0)" \
  --bad "$(c "$h4" 16)" --build-command "$cmd" --out "$t/kill" --jobs 2 --max-primitives 6 \
  --no-pictures --ways 3 >"$t/kill.out" 2>"$t/kill.err" &
victim=$!
pids+=("$victim")
for _ in $(seq 1200); do [ "$(grep -c '^bisect:   building .* in /' "$t/kill.err" 2>/dev/null)" = 3 ] && break; sleep 0.1; done
sleep 1
kill -9 "$victim"
wait "$victim" 2>/dev/null || true
[ "$(git -C "$h4" worktree list | wc -l)" = 4 ] || fail "kill -9 should leave the round's worktrees (the test proves nothing)"
"$ra" bisect "$t/run" --between faulty@good faulty@bad --source "$h4" --good "$(c "$h4" 0)" \
  --bad "$(c "$h4" 16)" --build-command "$cmd" --out "$t/kill" --jobs 2 --max-primitives 6 \
  --no-pictures --ways 1 >"$t/kill2.out" 2>"$t/kill2.err" || { cat "$t/kill2.err"; fail "after kill -9"; }
[ "$(culprits kill2)" = "c9: bad (6 primitives);" ] || fail "after kill -9: $(culprits kill2)"
no_worktrees "$h4"
[ "$(git -C "$h4" symbolic-ref --short HEAD)" = topic ] || fail "after kill -9 the tree is not back on its branch"
echo "bisect-ways-test: 9 bisections checked"
echo "1 passed, 0 failed"
