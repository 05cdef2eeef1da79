#!/usr/bin/env bash
# `renderaudit watch` under bad input, faults and signals, over a branch of stand-in builds
# (tests/scripts/bisect-fixture.sh), no compiler (ctest watch_faults). Each check is one guarantee of
# docs/reliability.md ("The nightly that follows a branch"):
#   refused before anything is built (exit 2, no night, nothing in the history): a truncated
#     watch.json, a commit or branch in it that git would read as an option, a platform that
#     cannot draw a build, a count the run refuses, a state folder that follows another tree;
#   an experiment path with a line break stays in the night's experiment.toml's comment;
#   SIGTERM during a night's bisection, SIGTERM or SIGINT during its run stop it (exit 128 + the
#     signal) with no audit row in the history;
#   changes that only failed builds separate from their cause are "unattributed:", not culprits;
#   a bisection that cannot run is "not bisected:" and its changes are bisected the next night;
#   a history that cannot be written keeps the "moved backwards" finding for the next night;
#   a fetch that fails and an upstream branch that is gone are errors (exit 2), said and recorded.
# Usage: tests/scripts/watch-faults-test.sh BUILD_DIR
. "$(dirname "$0")/test-common.sh"
. "$(dirname "$0")/bisect-fixture.sh"

forty_lines_toml watch-faults-test '"faulty"' $'[run]\nshard_timeout_s = 120' > "$t/nightly.toml"
# A driver that hangs on one primitive (a run that only a signal or its shard timeout ends).
mkdir -p "$t/drivers/hang"
printf '[faults]\nbase = "osmesa-llvmpipe"\nhang = [5]\n' > "$t/drivers/hang/faults.toml"
# The build of a "neither" commit waits while $t/slow exists (it says so in $t/sleeping), so that a
# signal can come during a night's bisection; the same command on every night (it keys the builds).
# The build of a "bad-stray" commit leaves an untracked file in the tree, which the night's
# bisection refuses (a tree that is not its commit cannot be bisected).
cp -r "$t/drivers/bad" "$t/drivers/bad-stray"
cmd='if [ -e '"$t"'/slow ] && [ "$(cat driver)" = neither ]; then touch '"$t"'/sleeping; sleep 300; fi; '\
'[ "$(cat driver)" != bad-stray ] || touch stray.txt; '"$cmd"
make_upstream "$t/mesa" good
watch() {  # watch NAME ARGS...: one night; exit code in $rc, output in $t/NAME.{out,err}
  local name=$1
  shift
  set +e
  "$ra" watch --build-command "$cmd" --jobs 2 --no-pictures "$@" >"$t/$name.out" 2>"$t/$name.err"
  rc=$?
  set -e
}
night() {  # night NAME [ARGS...]: a night of the main state folder
  local name=$1
  shift
  watch "$name" "$t/mesa" --experiment "$t/nightly.toml" --state "$t/state" "$@"
}
start_night() {  # start_night NAME: a night of the main state folder in the background, its pid in $pid
  "$ra" watch --build-command "$cmd" --jobs 2 --no-pictures "$t/mesa" --experiment "$t/nightly.toml" \
    --state "$t/state" >"$t/$1.out" 2>"$t/$1.err" &
  pid=$!
  pids+=("$pid")
}
show() { cat "$t/$1.out" "$t/$1.err"; }
expect() {  # expect NAME CODE TEXT: said on stdout
  [ "$rc" = "$2" ] && grep -qF -- "$3" "$t/$1.out" ||
    { show "$1"; fail "$1: exit $rc (expected $2), '$3' not said"; }
}
refused() {  # refused NAME STATE TEXT...: exit 2, each TEXT said on stderr, no night in STATE
  local name=$1 state=$2 text
  shift 2
  [ "$rc" = 2 ] || { show "$name"; fail "$name: exit $rc, not 2"; }
  for text in "$@"; do
    grep -qF -- "$text" "$t/$name.err" || { show "$name"; fail "$name: '$text' not said"; }
  done
  ! grep -qE "^night:|json.exception|parse_error" "$t/$name.out" "$t/$name.err" ||
    { show "$name"; fail "$name: a night or a JSON library message"; }
  [ ! -e "$state/nights" ] || { show "$name"; fail "$name: made a night folder"; }
}
audits() {  # the number of audit rows in the main state's history
  "$ra" history --db "$t/state/history.sqlite" >"$t/audits.out" 2>&1 || { cat "$t/audits.out"; fail "history"; }
  sed -n 's/^.*: \([0-9][0-9]*\) audits\{0,1\}\( (nothing\|, the last\).*$/\1/p' "$t/audits.out"
}
c0=$(c "$up" 0)

# Bad state: refused before the tree is touched or anything built, naming the file and the key.
mkdir -p "$t/s-cut"
printf '{"commit": "%s", "build_d' "$c0" > "$t/s-cut/watch.json"
watch cut "$t/mesa" --experiment "$t/nightly.toml" --state "$t/s-cut"
refused cut "$t/s-cut" "$t/s-cut/watch.json: not a whole JSON document" "remove the file"
mkdir -p "$t/s-opt"
printf '{"commit": "--output=%s", "build_dir": "%s", "branch": "main"}' "$t/PWNED" "$t" > "$t/s-opt/watch.json"
watch option-commit "$t/mesa" --experiment "$t/nightly.toml" --state "$t/s-opt"
refused option-commit "$t/s-opt" "$t/s-opt/watch.json: commit: must be a full commit hash"
[ ! -e "$t/PWNED" ] || fail "a commit in watch.json reached git as an option"
printf '{"commit": "%s", "build_dir": "%s", "branch": "--orphan=pwned"}' "$c0" "$t" > "$t/s-opt/watch.json"
git -C "$t/mesa" checkout -q --detach
watch option-branch "$t/mesa" --experiment "$t/nightly.toml" --state "$t/s-opt"
refused option-branch "$t/s-opt" "$t/s-opt/watch.json: branch: must be a branch name, never starting with '-'"
git -C "$t/mesa" rev-parse -q --verify HEAD >/dev/null || fail "a branch in watch.json reached git as an option"
git -C "$t/mesa" checkout -q main

# A bad experiment: refused before tonight's build (the build cache stays empty).
sed 's/platforms = \["faulty"\]/platforms = ["reference"]/' "$t/nightly.toml" > "$t/reference.toml"
watch reference "$t/mesa" --experiment "$t/reference.toml" --state "$t/s-exp"
refused reference "$t/s-exp" "$t/reference.toml: platforms: 'reference' cannot draw a driver build"
sed 's/^lines = 40/lines = -5/' "$t/nightly.toml" > "$t/negative.toml"
watch negative "$t/mesa" --experiment "$t/negative.toml" --state "$t/s-exp"
refused negative "$t/s-exp" "$t/negative.toml:"
[ ! -e "$t/s-exp/history.sqlite" ] || fail "a bad experiment was recorded in the history"
[ -z "$(ls -A "$t/cache" 2>/dev/null)" ] || fail "a bad experiment was refused after a build"

# The experiment's path reaches the night's experiment.toml only inside its comment.
hostile="$t/nightly"$'\n'"run.shard_size = 7 #"$'\n'"[bogus]"$'\n'"#.toml"
cp "$t/nightly.toml" "$hostile"
watch hostile "$t/mesa" --experiment "$hostile" --state "$t/s-hostile"
expect hostile 0 "night: baseline established"
! grep -qE '^(run\.shard_size|\[bogus\])' "$t"/s-hostile/nights/*/experiment.toml ||
  { cat "$t"/s-hostile/nights/*/experiment.toml; fail "the experiment's path became TOML of the night's experiment"; }

night 1
expect 1 0 "night: baseline established"

# Another tree with this state: refused, naming the tree the state follows.
make_history "$t/other" good bad
watch other "$t/other" --experiment "$t/nightly.toml" --state "$t/state"
[ "$rc" = 2 ] && grep -qF "follows the tree $t/mesa, not $t/other" "$t/other.err" ||
  { show other; fail "a state folder of another tree: exit $rc"; }
grep -q "\"commit\": \"$c0\"" "$t/state/watch.json" || fail "the state switched to another tree"
[ "$(audits)" = 0 ] || fail "night 1 made audit rows"

# SIGTERM during the bisection: exit 143, the night unrecorded, no audit row in the history.
commit good neither bad
touch "$t/slow"
start_night bisect-term
while [ ! -e "$t/sleeping" ]; do
  kill -0 "$pid" 2>/dev/null || { wait "$pid" || true; show bisect-term; fail "the night ended before its bisection"; }
  sleep 0.2
done
kill -TERM "$pid"
set +e; wait "$pid"; rc=$?; set -e
rm -f "$t/slow" "$t/sleeping"
[ "$rc" = 143 ] || { show bisect-term; fail "SIGTERM during the bisection: exit $rc, not 143"; }
[ "$(audits)" = 0 ] || fail "SIGTERM during the bisection left an audit row in the history"
night 3
expect 3 1 "night: changed: 40 primitives changed, 2 culprit commit(s)"
[ "$(audits)" = 1 ] || fail "night 3's audit is not in the history"

# Changes only failed builds separate from their cause: not culprits, and not called a sample.
commit broken good
night unattributed
expect unattributed 1 "night: changed: 40 primitives changed, 0 culprit commit(s), 40 change(s) not attributed"
expect unattributed 1 "unattributed: 40 changes of faulty: only commits that failed to build"
! grep -qE "^first bad commit:|a sample" "$t/unattributed.out" || { show unattributed; fail "unattributed changes said as culprits or a sample"; }

# A bisection that cannot run: its changes are not culprits, and they are kept: the baseline
# stays, so that the next night bisects them.
commit bad-stray
night stray
expect stray 1 "not bisected: faulty: "
! grep -q "^first bad commit:" "$t/stray.out" || { show stray; fail "a bisection that could not run printed a first bad commit"; }
c5=$(c "$up" 5)
grep -q "\"commit\": \"$c5\"" "$t/state/watch.json" || fail "a night whose bisection could not run moved the baseline"
rm "$t/mesa/stray.txt"
night stray-again
expect stray-again 1 "first bad commit: $(c "$up" 6) c6: bad-stray (40 primitives of faulty)"
c6=$(c "$up" 6)

# SIGTERM or SIGINT during the run (a driver that hangs): the run is stopped, not waited for (it
# would end at the hung primitive's shard timeout), no audit, watch.json stays.
commit hang
n_audits=$(audits)
for sig in TERM INT; do
  start_night "run-$sig"
  until grep -q "^watch: run: " "$t/run-$sig.err" 2>/dev/null; do
    kill -0 "$pid" 2>/dev/null || { wait "$pid" || true; show "run-$sig"; fail "the night ended before its run"; }
    sleep 0.2
  done
  kill "-$sig" "$pid"
  set +e; wait "$pid"; rc=$?; set -e
  want=$((128 + $(kill -l "$sig")))
  [ "$rc" = "$want" ] || { show "run-$sig"; fail "SIG$sig during the run: exit $rc, not $want"; }
  [ "$(audits)" = "$n_audits" ] || fail "SIG$sig during the run left an audit row in the history"
  run_dir=$(sed -n 's|^watch: run: \(.*\)/experiment.toml$|\1/run|p' "$t/run-$sig.err")
  ! grep -qs '"status": "complete' "$run_dir/manifest.json" || fail "SIG$sig during the night's run let the run finish"
  grep -q "\"commit\": \"$c6\"" "$t/state/watch.json" || fail "an interrupted night moved watch.json"
done

# A history that cannot be written: the "moved backwards" finding is kept for the next night.
git -C "$up" reset -q --hard "$(c "$up" 1)"
touch "$t/not-a-folder"
night unwritable --db "$t/not-a-folder/history.sqlite"
[ "$rc" = 2 ] || { show unwritable; fail "an unwritable history: exit $rc, not 2"; }
grep -l "moved backwards" "$t"/state/nights/*/night.md >/dev/null 2>&1 || fail "the unrecorded night wrote no night.md"
night 6
expect 6 1 "night: moved backwards"

# Upstream that cannot be seen: an error, said and recorded, never "nothing new".
commit bad
git -C "$t/mesa" remote set-url origin "$t/nowhere"
night 7
expect 7 2 "night: fetch failed"
git -C "$t/mesa" remote set-url origin "$up"
git -C "$up" branch -q -m main trunk
night 8
expect 8 2 "night: upstream gone"
git -C "$up" branch -q -m trunk main
night 9
expect 9 1 "night: changed"

"$ra" history --db "$t/state/history.sqlite" >"$t/history.out" 2>&1 || { cat "$t/history.out"; fail "history"; }
for v in "fetch failed" "upstream gone"; do
  grep -qE "  $v  " "$t/history.out" || { cat "$t/history.out"; fail "history: no '$v' night"; }
done
echo "watch-faults-test: checked"
echo "1 passed, 0 failed"
