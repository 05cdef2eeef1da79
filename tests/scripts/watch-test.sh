#!/usr/bin/env bash
# `renderaudit watch` over six nights of a Mesa branch made of stand-in builds
# (tests/scripts/bisect-fixture.sh), no compiler (ctest watch_nights). The watched tree is a clone that
# follows an upstream; each night commits to the upstream first:
#   1. c0 good:                      baseline established (exit 0)
#   2. nothing new:                  said, nothing built or run (exit 0)
#   3. c1 good, c2 neither, c3 bad:  changed; the even lines named to c2, the odd ones to c3 (exit 1)
#   4. c4 broken:                    build failed; last night's build stays the baseline (exit 2)
#   5. c5 bad, the tree left detached at c2 (a bisection killed mid-step):
#                                    back on its branch, unchanged against c3 (exit 0)
#   6. upstream reset to c1:         moved backwards; tonight is the new baseline (exit 1)
# and `history` lists the six nights with their commits, verdicts and culprits.
# Usage: tests/scripts/watch-test.sh BUILD_DIR
. "$(dirname "$0")/test-common.sh"
. "$(dirname "$0")/bisect-fixture.sh"

forty_lines_toml watch-test '"faulty"' > "$t/nightly.toml"
make_upstream "$t/mesa" good
night() {  # night N: one night; exit code in $rc, output in $t/nightN.{out,err}
  set +e
  "$ra" watch "$t/mesa" --experiment "$t/nightly.toml" --state "$t/state" --build-command "$cmd" \
    --jobs 2 --no-pictures >"$t/night$1.out" 2>"$t/night$1.err"
  rc=$?
  set -e
}
expect() {  # expect N CODE TEXT
  [ "$rc" = "$2" ] && grep -qF -- "$3" "$t/night$1.out" ||
    { cat "$t/night$1.out" "$t/night$1.err"; fail "night $1: exit $rc (expected $2), '$3' not said"; }
}

night 1
expect 1 0 "night: baseline established"
night 2
expect 2 0 "night: nothing new"
grep -q "^details:" "$t/night2.out" && fail "night 2 made a night folder"
commit good neither bad
night 3
expect 3 1 "night: changed: 40 primitives changed, 2 culprit commit(s)"
c2=$(c "$up" 2)
expect 3 1 "first bad commit: $c2 c2: neither (20 primitives of faulty)"
expect 3 1 "first bad commit: $(c "$up" 3) c3: bad (20 primitives of faulty)"
# The night's bisection report repeats a command that runs, not a description of one.
repeat=$(grep -A3 '^## Repeat it' "$t"/state/nights/*/bisect-faulty/bisect.md || true)
grep -qF -- "renderaudit bisect $t/state/nights/" <<<"$repeat" ||
  fail "night 3's bisection report has no command to repeat"
grep -qF -- "--between faulty@watch-last faulty@watch-tonight --source $t/mesa --good $(c "$up" 0)" <<<"$repeat" ||
  fail "night 3's Repeat it is not the bisection it ran"
commit broken
night 4
expect 4 2 "night: build failed: the build of $(c "$up" 4 | cut -c1-12) failed ("
# One line on stdout, the whole error in its file; night.md says it as a sentence.
failed_line=$(grep 'night: build failed' "$t/night4.out" || true)
[ "$(grep -c 'build-error.txt' "$t/night4.out")" = 1 ] && [[ $failed_line == *build-error.txt* ]] ||
  { cat "$t/night4.out"; fail "night 4's build failure is not one line naming build-error.txt"; }
night4_md="$(ls -d "$t"/state/nights/* | tail -1)/night.md"
sentence=$(sed -n 3p "$night4_md")
[[ $sentence == "The build of "* ]] || fail "night 4's night.md does not start with what failed: $sentence"
grep -q "\"commit\": \"$(c "$up" 3)\"" "$t/state/watch.json" || fail "night 4 replaced the last good build"
commit bad
git -C "$t/mesa" checkout -q --detach "$(c "$up" 2)"
night 5
expect 5 0 "night: unchanged: no primitive changed ($(c "$up" 5 | cut -c1-12))"
grep -qF "watch: returning $t/mesa to its branch main" "$t/night5.err" || fail "night 5 did not say it returned the tree to its branch"
git -C "$up" reset -q --hard "$(c "$up" 1)"
night 6
expect 6 1 "night: moved backwards"

"$ra" history --db "$t/state/history.sqlite" >"$t/history.out" 2>&1 || { cat "$t/history.out"; fail "history"; }
nights=$(sed -n '/nights of renderaudit watch/,/audits, the last/p' "$t/history.out")
n=0
for v in "baseline established" "nothing new" "changed" "build failed" "unchanged" "moved backwards"; do
  n=$((n + 1))
  grep -qE "^ *#$n  .*  $v  " <<< "$nights" || { cat "$t/history.out"; fail "history: night $n is not '$v'"; }
done
grep -qF "culprit: $c2 c2: neither (20 primitives of faulty)" <<< "$nights" ||
  { cat "$t/history.out"; fail "history lacks night 3's culprits"; }
echo "watch-test: 6 nights checked"
echo "1 passed, 0 failed"
