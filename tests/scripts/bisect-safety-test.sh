#!/usr/bin/env bash
# One writer per Mesa tree, builds that prove their commit, and bisections that leave the tree as
# they found it (ctest bisect_safety), with the stand-in builds of tests/scripts/bisect-fixture.sh:
#   - a second bisection, or `builds build --ref`, on a tree a bisection is using is refused,
#     naming the holder, and the first bisection's answer is right;
#   - a build whose tree moved under it is not kept (a tree without git keyed on its content:
#     builds/source_build_test.cpp);
#   - SIGTERM stops the build command's whole process group and restores the branch (exit 143);
#     after kill -9, the same command restores the branch and resumes;
#   - bad inputs (an untracked file in the tree too, an --out inside the tree) are refused before
#     anything is built; a damaged bisect.json (its seal), a bad field, a drawing that lacks a
#     primitive and an original head git would read as an option are named with file and key, exit 2;
#   - `builds build --ref` refuses a tree with an untracked file, and a cached build without the
#     proof that its tree was clean is built again, not reused;
#   - `builds remove` refuses the builds a watch night draws with, and the next night rebuilds a
#     baseline build that was removed.
# Usage: tests/scripts/bisect-safety-test.sh BUILD_DIR
. "$(dirname "$0")/test-common.sh"
on_exit='pkill -f "sleep 29\.7" 2>/dev/null || true'
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
run_ra "$t/inside.out" bisect "${bisect_args[@]}" --out "$g/bout"
expect 2 "$t/inside.out" "--out $g/bout is inside the source tree $g"
[ ! -e "$g/bout" ] || fail "a bisection into the source tree made its folder there"
[ "$(ls "$t/cache" | wc -l)" = "$before" ] || fail "a refused bisection built something"
# Damaged copies of a finished bisection's bisect.json, each resumed into a folder of its own:
# the file and the key named, exit 2, the tree left on its branch. (v2: rewritten as a file of
# version 2, from before the seal, whose fields are then checked one by one.)
damaged() {  # damaged NAME PYTHON: bisect.json edited by PYTHON (j: the document), then resumed
  mkdir -p "$t/$1"
  /usr/bin/python3 - "$t/kill/bisect.json" "$t/$1/bisect.json" "$2" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
def v2():
    j.pop("seal"); j["schema_version"] = 2
exec(sys.argv[3])
json.dump(j, open(sys.argv[2], "w"), indent=2)
PY
  run_ra "$t/$1.out" bisect "${bisect_args[@]}" --out "$t/$1"
}
damaged flipped 'p = j["steps"][0]["drawing"]["primitives"]; l = sorted(p)[0]
h = p[l]["pixel_hash"]; p[l]["pixel_hash"] = h[:-1] + str((int(h[-1]) + 1) % 10)'
expect 2 "$t/flipped.out" "$t/flipped/bisect.json: 'seal' does not match the content"
damaged field 'v2(); p = j["steps"][0]["drawing"]["primitives"]; p[sorted(p)[0]]["pixel_hash"] = "x"'
expect 2 "$t/field.out" "$t/field/bisect.json: 'steps[0].drawing.primitives[\"line "
grep -q "pixel_hash' must be a decimal 64-bit number" "$t/field.out" || { cat "$t/field.out"; fail "the key"; }
damaged no-good 'v2(); p = j["good"]["drawing"]["primitives"]; del p[sorted(p)[0]]'
expect 2 "$t/no-good.out" "$t/no-good/bisect.json: 'good.drawing.primitives[\"line "
grep -q "is missing; move the file away" "$t/no-good.out" || { cat "$t/no-good.out"; fail "no-good: the key"; }
damaged no-step 'v2(); p = j["steps"][0]["drawing"]["primitives"]; del p[sorted(p)[0]]'
expect 2 "$t/no-step.out" "$t/no-step/bisect.json: 'steps[0].drawing.primitives[\"line "
git -C "$g" checkout -q --detach   # as a kill -9 mid-step leaves it: the resume checks out the head
damaged orphan 'v2(); j["original_head"] = "--orphan=pwned"'
expect 2 "$t/orphan.out" "$t/orphan/bisect.json: 'original_head' must be the branch the tree was on"
git -C "$g" rev-parse -q --verify HEAD >/dev/null || fail "the tree was left on an empty orphan branch"
git -C "$g" checkout -q main

# 5. A build is its commit's: a tree with an untracked file is refused for --ref, and a cached
# build that does not record a clean tree is built again.
echo stale > "$g/meson.options"
run_ra "$t/untracked-build.out" builds build "$g" --ref "$(c "$g" 3)" --build-command "$cmd"
expect 2 "$t/untracked-build.out" "has 1 untracked file (meson.options); a build of $(c "$g" 3) would see it"
rm "$g/meson.options"
run_ra "$t/c4.out" builds build "$g" --ref "$(c "$g" 4)" --build-command "$cmd"
expect 0 "$t/c4.out" "reused: same source and options"
c4_dir=$(sed -n 's/^  folder: //p' "$t/c4.out")
/usr/bin/python3 - "$c4_dir/build.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
del j["source_build"]["clean"]   # as a build made before the proof, maybe of a tainted tree
json.dump(j, open(sys.argv[1], "w"))
PY
# (A bisection of c3..c4 builds c4 again; `builds build` would too, then stop at its probe, which
# the stand-in builds cannot pass.)
run_ra "$t/proof.out" bisect "$t/run" --between faulty@good faulty@bad --source "$g" \
  --good "$(c "$g" 3)" --bad "$(c "$g" 4)" --build-command "$cmd" --max-primitives 4 --no-pictures \
  --jobs 2 --out "$t/proof"
expect 0 "$t/proof.out" "built $(basename "$c4_dir") in"
grep -q "reused build $(basename "$c4_dir")" "$t/proof.out" && fail "a build without the proof was reused"

# 6. The builds a watch night draws with are not removed under it (the night is stopped with
# SIGSTOP once its run is set up, its build done and the tree free), and a night whose baseline
# build was removed builds it again.
export RENDERAUDIT_BUILD_CACHE="$t/cache-watch"
make_upstream "$t/wmesa" good
sed -e 's/^platforms = .*/platforms = ["faulty"]/' -e '/^\[builds/,/^dir/d' \
    -e 's/^lines = .*/lines = 400/' "$t/exp.toml" > "$t/nightly.toml"
watch_args=("$t/wmesa" --experiment "$t/nightly.toml" --state "$t/wstate" --build-command "$cmd"
            --jobs 2 --no-pictures)
"$ra" watch "${watch_args[@]}" >"$t/night1.out" 2>"$t/night1.err" ||
  { cat "$t/night1.out" "$t/night1.err"; fail "night 1"; }
commit bad
"$ra" watch "${watch_args[@]}" >"$t/night2.out" 2>"$t/night2.err" &
victim=$!
pids+=("$victim")
# (night 1's folder holds its experiment.toml already: tonight's is the second)
for _ in $(seq 600); do
  [ "$(ls "$t"/wstate/nights/*/experiment.toml 2>/dev/null | wc -l)" = 2 ] && break
  sleep 0.05
done
kill -STOP "$victim"
mapfile -t wbuilds < <(ls "$RENDERAUDIT_BUILD_CACHE" | grep '^mesa-')
[ ${#wbuilds[@]} = 2 ] || fail "the night's two builds: ${wbuilds[*]}"
run_ra "$t/remove-busy.out" builds remove "${wbuilds[@]}"
expect 2 "$t/remove-busy.out" "is in use: a process draws with it now"
kill -CONT "$victim"
set +e
wait "$victim"
rc=$?
set -e
[ $rc = 1 ] || { cat "$t/night2.out" "$t/night2.err"; fail "night 2 exited $rc"; }
tonight=$(ls "$RENDERAUDIT_BUILD_CACHE" | grep "^mesa-$(git -C "$up" rev-parse HEAD | cut -c1-12)")
run_ra "$t/remove-baseline.out" builds remove "$tonight"
expect 0 "$t/remove-baseline.out" "removed $tonight ("
commit bad
set +e
"$ra" watch "${watch_args[@]}" >"$t/night3.out" 2>"$t/night3.err"
rc=$?
set -e
[ $rc = 0 ] || { cat "$t/night3.out" "$t/night3.err"; fail "night 3 (baseline build removed) exited $rc"; }
grep -q "no longer holds the build of $(git -C "$up" rev-parse HEAD~1 | cut -c1-12): building it again" "$t/night3.err" ||
  { cat "$t/night3.err"; fail "night 3 did not say it built the baseline again"; }
echo "bisect-safety-test: 6 groups checked"
echo "1 passed, 0 failed"
