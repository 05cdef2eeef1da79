#!/usr/bin/env bash
# One writer per Mesa tree, builds that prove their commit, and bisections that leave the tree as
# they found it (ctest bisect_safety), with the stand-in builds of scripts/bisect-fixture.sh:
#   - a second bisection, or `builds build --ref`, on a tree a bisection is using is refused,
#     naming the holder, and the first bisection's answer is right;
#   - a build whose tree moved under it is not kept (a tree without git keyed on its content:
#     runner/source_build_test.cpp);
#   - SIGTERM stops the build command's whole process group and restores the branch (exit 143);
#     after kill -9, the same command restores the branch and resumes;
#   - bad inputs (an untracked file in the tree too) are refused before anything is built; a bad field of bisect.json is named.
# Usage: scripts/bisect-safety-test.sh BUILD_DIR
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
t=$(mktemp -d /tmp/renderaudit-bisect-safety-XXXXXX)
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done
  pkill -f "sleep 29\.7" 2>/dev/null || true
  [ -n "${KEEP:-}" ] || rm -rf "$t"
}
trap cleanup EXIT
. "$(dirname "$0")/bisect-fixture.sh"
make_run
g="$t/mesa"
make_history "$g" good good good good bad bad bad bad
good=$(c "$g" 0) bad=$(c "$g" 7)
bisect_args=("$t/run" --between faulty@good faulty@bad --source "$g" --good "$good" --bad "$bad"
             --build-command "$cmd" --max-primitives 4 --no-pictures --jobs 2)
expect() {  # expect CODE FILE TEXT: the last command's exit code and a line of its output
  [ "$rc" = "$1" ] || { cat "$2"; fail "exit $rc, expected $1 ($3)"; }
  grep -qF -- "$3" "$2" || { cat "$2"; fail "'$3' not said"; }
}
run_ra() {  # run_ra OUTFILE ARGS...: rc set
  local out=$1
  shift
  set +e
  "$ra" "$@" >"$out" 2>&1
  rc=$?
  set -e
}

# 1. One writer per tree: a second bisection and a `builds build --ref` are refused while the
# first builds (each build sleeps 2 s), and the first's answer is right.
RA_TEST_SLEEP=2 "$ra" bisect "${bisect_args[@]}" --out "$t/first" >"$t/first.out" 2>"$t/first.err" &
first=$!
pids+=("$first")
for _ in $(seq 50); do grep -q "building" "$t/first.err" 2>/dev/null && break; sleep 0.2; done
run_ra "$t/second.out" bisect "${bisect_args[@]}" --out "$t/second"
expect 2 "$t/second.out" "(bisect) on host"
run_ra "$t/build.out" builds build "$g" --ref "$(c "$g" 2)" --build-command "$cmd"
expect 2 "$t/build.out" "one build or bisection at a time checks out commits in $g"
wait "$first" || { cat "$t/first.err"; fail "the first bisection failed"; }
[ "$(grep '^first bad commit' "$t/first.out")" = "first bad commit: $(c "$g" 4) c4: bad (4 primitives)" ] ||
  { cat "$t/first.out"; fail "the first bisection's answer"; }

# 2. A build whose tree moved under it is not kept.
run_ra "$t/moved.out" builds build "$g" --ref "$(c "$g" 3)" --name moved \
  --build-command "git checkout -q $(c "$g" 5); $cmd"
expect 2 "$t/moved.out" "changed while it was built (HEAD was $(c "$g" 3 | cut -c1-12), is now $(c "$g" 5 | cut -c1-12))"
[ ! -e "$t/cache/moved" ] || fail "the moved build was kept"
[ "$(git -C "$g" symbolic-ref --short HEAD)" = main ] || fail "builds build did not restore the branch"
# 3. SIGTERM during a build: the build command's group stopped, the branch restored, exit 143.
# (A cache of its own: the builds above would be reused and nothing would be built.)
export RENDERAUDIT_BUILD_CACHE="$t/cache-signals"
RA_TEST_SLEEP=29.7 "$ra" bisect "${bisect_args[@]}" --out "$t/term" >"$t/term.out" 2>"$t/term.err" &
victim=$!
pids+=("$victim")
for _ in $(seq 50); do pgrep -f "sleep 29\.7" >/dev/null && break; sleep 0.2; done
kill -TERM "$victim"
set +e
wait "$victim"
rc=$?
set -e
[ $rc = 143 ] || { cat "$t/term.err"; fail "SIGTERM: exit $rc"; }
sleep 0.5
pgrep -f "sleep 29\.7" >/dev/null && fail "the build command's child outlived the bisection"
[ "$(git -C "$g" symbolic-ref --short HEAD)" = main ] || fail "SIGTERM left HEAD detached"
grep -q "interrupted by SIGTERM" "$t/term.err" || fail "SIGTERM was not said"
# kill -9 during a build: the tree is left at the good ref; the same command restores the branch.
RA_TEST_SLEEP=29.7 "$ra" bisect "${bisect_args[@]}" --out "$t/kill" >"$t/kill.out" 2>"$t/kill.err" &
victim=$!
pids+=("$victim")
for _ in $(seq 50); do pgrep -f "sleep 29\.7" >/dev/null && break; sleep 0.2; done
kill -9 "$victim"
wait "$victim" || true
pkill -f "sleep 29\.7" || true
git -C "$g" symbolic-ref -q HEAD >/dev/null && fail "kill -9 should leave HEAD detached (the test proves nothing)"
run_ra "$t/resume.out" bisect "${bisect_args[@]}" --out "$t/kill"
expect 0 "$t/resume.out" "returning $g to main, where the interrupted bisection found it"
[ "$(git -C "$g" symbolic-ref --short HEAD)" = main ] || fail "the resume left HEAD detached"

# 4. Inputs refused before anything is built.
export RENDERAUDIT_BUILD_CACHE="$t/cache"
before=$(ls "$t/cache" | wc -l)
run_ra "$t/same.out" bisect "${bisect_args[@]/$bad/$good}" --out "$t/same"
expect 2 "$t/same.out" "are the same commit"
run_ra "$t/view.out" bisect "$t/run" --primitive line:9:1 --source "$g" --good "$good" --bad "$bad" \
  --platform faulty --build-command "$cmd" --out "$t/view"
expect 2 "$t/view.out" "the run has views 1-1"
touch "$t/a-file"
run_ra "$t/file.out" bisect "${bisect_args[@]}" --out "$t/a-file"
expect 2 "$t/file.out" "is a file; --out names a folder"
run_ra "$t/platform.out" bisect "$t/run" --between faulty@good faulty@newer --source "$g" \
  --good "$good" --bad "$bad" --build-command "$cmd" --out "$t/platform"
expect 2 "$t/platform.out" "names platform 'faulty@newer', which $t/run did not draw (it has: faulty@good, faulty@bad)"
echo stale > "$g/meson.options"   # what a checkout that failed half-way leaves behind
run_ra "$t/untracked.out" bisect "${bisect_args[@]}" --out "$t/untracked"
expect 2 "$t/untracked.out" "has 1 untracked file (meson.options); every step's build would see it"
rm "$g/meson.options"
[ "$(ls "$t/cache" | wc -l)" = "$before" ] || fail "a refused bisection built something"
# A bad field of bisect.json: the file and the key, exit 2.
sed -i 's/"pixel_hash": "[0-9]*"/"pixel_hash": "x"/' "$t/kill/bisect.json"
run_ra "$t/json.out" bisect "${bisect_args[@]}" --out "$t/kill"
expect 2 "$t/json.out" "$t/kill/bisect.json: 'steps[0].drawing.primitives[\"line "
grep -q "pixel_hash' must be a decimal 64-bit number" "$t/json.out" || { cat "$t/json.out"; fail "the key"; }
echo "bisect-safety-test: 4 groups checked"
echo "1 passed, 0 failed"
