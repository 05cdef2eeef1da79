#!/usr/bin/env bash
# `renderaudit bisect --speed` and `watch --speed` end to end with real drawing and no compiler
# (ctest bisect_speed): stand-in builds (tests/scripts/bisect-fixture.sh) that draw the same pixels and
# differ in drawing time only, through the faulty platform's [faults] slowdown (a busy wait inside
# the timed drawing: the build draws those kinds three times as long).
#   lines-slow: lines slowed;  both-slow: lines and triangles;  tris-slow: triangles only;
#   plain: timed, nothing slowed;  plain-bad: plain with a wild pixel per primitive (pixels change).
# Checked:
#   - history c0..c6 = lines-slow lines-slow both-slow both-slow both-slow tris-slow tris-slow:
#     one bisection names c2 (triangles slower) and c5 (lines faster), no pixel culprit, each
#     line with its confirmed ratio; bisect.json and bisect.md carry them;
#   - refs that differ neither in pixels nor in time: nothing named (exit 2);
#   - one commit that changes both pixels and time: named for both;
#   - with paths: a culprit timed beside its git parent, not the paths' previous commit; a move
#     in a commit the paths leave out unattributed, with the bisection without paths;
#   - a watch night whose time moved: the audit finds it, the night names the slower commit;
#     --keep-nights 1 leaves tonight's folder only.
# Usage: tests/scripts/bisect-speed-test.sh BUILD_DIR
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
t=$(mktemp -d /tmp/renderaudit-bisect-speed-test-XXXXXX)
trap '[ -n "${KEEP:-}" ] || rm -rf "$t"' EXIT
. "$(dirname "$0")/bisect-fixture.sh"

base='[faults]\nbase = "osmesa-llvmpipe"\n'
mkdir -p "$t/drivers"/{lines-slow,both-slow,tris-slow,plain,plain-bad}
printf "$base"'slowdown = 2\nslowdown_kinds = ["line"]\n' > "$t/drivers/lines-slow/faults.toml"
printf "$base"'slowdown = 2\n' > "$t/drivers/both-slow/faults.toml"
printf "$base"'slowdown = 2\nslowdown_kinds = ["triangle"]\n' > "$t/drivers/tris-slow/faults.toml"
printf "$base"'slowdown = 0\n' > "$t/drivers/plain/faults.toml"
printf "$base"'slowdown = 0\nwild_pixel = [%s]\n' "$(seq -s, 0 59)" > "$t/drivers/plain-bad/faults.toml"

# 60 lines and 60 triangles of one 256 x 256 FOV-150 view: llvmpipe's tens of microseconds each.
experiment() {  # experiment GOOD_DRIVER BAD_DRIVER
  printf 'name = "bisect-speed-test"\nseed = 5\nplatforms = ["faulty@good", "faulty@bad"]\n'
  printf '[views]\norientations = 1\nfov_deg = [150]\nwindows = [256]\nnear = 0.01\nfar = 10.0\n'
  printf '[primitives]\npoints = 0\nlines = 60\ntriangles = 60\n'
  printf '[builds.good]\ndir = "%s"\n[builds.bad]\ndir = "%s"\n' "$t/drivers/$1" "$t/drivers/$2"
}
run() {  # run NAME GOOD_DRIVER BAD_DRIVER
  experiment "$2" "$3" > "$t/$1.toml"
  "$ra" run "$t/$1.toml" --out "$t/$1" --jobs 2 --quiet >/dev/null 2>"$t/$1.log" ||
    { cat "$t/$1.log"; fail "run $1"; }
}
bisect() {  # bisect NAME RUN HISTORY GOOD BAD [options]: exit code in $rc
  local name=$1 run=$2 g=$3 good=$4 bad=$5
  shift 5
  set +e
  "$ra" bisect "$t/$run" --between faulty@good faulty@bad --source "$g" --good "$good" \
    --bad "$bad" --build-command "$cmd" --out "$t/$name" --jobs 2 --no-pictures --speed \
    --speed-repeats "${REPEATS:-8}" --speed-primitives 60 "$@" >"$t/$name.out" 2>"$t/$name.err"
  rc=$?
  set -e
}
show() { cat "$t/$1.out" "$t/$1.err"; }

# One bisection, two culprits of time: triangles slower at c2, lines faster at c5.
run speed lines-slow tris-slow
g="$t/mesa"
make_history "$g" lines-slow lines-slow both-slow both-slow both-slow tris-slow tris-slow
bisect b1 speed "$g" "$(c "$g" 0)" "$(c "$g" 6)"
[ $rc -eq 0 ] || { show b1; fail "bisect --speed exited $rc"; }
grep -q "^first bad commit:" "$t/b1.out" && { show b1; fail "a pixel culprit where no pixel changed"; }
grep -qE "^first slower commit: $(c "$g" 2) c2: both-slow \(triangles, view group A: [0-9.]+x \[[0-9.]+, [0-9.]+\]\)$" "$t/b1.out" ||
  { show b1; fail "c2 not named as the first slower commit of triangles"; }
grep -qE "^first faster commit: $(c "$g" 5) c5: tris-slow \(lines, view group A: [0-9.]+x \[[0-9.]+, [0-9.]+\]\)$" "$t/b1.out" ||
  { show b1; fail "c5 not named as the first faster commit of lines"; }
[ "$(grep -c '^first \(slower\|faster\) commit:' "$t/b1.out")" = 2 ] || { show b1; fail "more than two time culprits"; }
/usr/bin/python3 - "$t/b1/bisect.json" "$(c "$g" 2)" "$(c "$g" 5)" <<'PY' || fail "bisect.json of b1"
import json, sys
j = json.load(open(sys.argv[1]))
assert j["complete"] and not j["culprits"] and not j["speed_unattributed"], j
ends = {(e["kind"], e["group"]): e for e in j["speed_ends"]}
assert ends[("triangle", "A")]["verdict"] == "slower", ends
assert ends[("line", "A")]["verdict"] == "faster", ends
# The busy wait triples a slowed primitive's time: the ratio is about 3 (other on a loaded
# machine, whose noise falls on some rounds more than others).
assert ends[("triangle", "A")]["low"] > 1.5, ends
assert ends[("line", "A")]["high"] < 1 / 1.5, ends
culprits = {c["commit"]: c for c in j["speed_culprits"]}
assert set(culprits) == {sys.argv[2], sys.argv[3]}, culprits
slower = culprits[sys.argv[2]]["moves"]
assert [(m["kind"], m["direction"], m["verdict"]) for m in slower] == [("triangle", "slower", "slower")], slower
assert slower[0]["low"] > 1.5, slower
faster = culprits[sys.argv[3]]["moves"]
assert [(m["kind"], m["direction"], m["verdict"]) for m in faster] == [("line", "faster", "faster")], faster
assert faster[0]["high"] < 1 / 1.5, faster
# Each step timed only the groups whose range holds it; no commit built twice.
commits = [s["commit"] for s in j["steps"]]
assert len(commits) == len(set(commits)) <= 5, commits
for s in j["steps"]:
    assert 1 <= len(s["speed"]) <= 2, s
    for t in s["speed"]:
        assert t["place"] in ("as good", "as bad"), s
PY
for part in "drawing time of 2 groups moved, 2 commits" "## Drawing time" "Drawing time: $(c "$g" 2 | cut -c1-12) c2: both-slow" \
  "**How it was found.**" "the triangles, view group A slower" "--speed --speed-repeats 8 --speed-primitives 60"; do
  grep -qF -- "$part" "$t/b1/bisect.md" || fail "bisect.md lacks '$part'"
done

# Refs alike in pixels and time: nothing to attribute.
bisect b2 speed "$g" "$(c "$g" 0)" "$(c "$g" 1)"
[ $rc -eq 2 ] && grep -q "no group's drawing time moved" "$t/b2.err" || { show b2; fail "refs alike: exit $rc"; }

# One commit that changes pixels and time: the wild pixel the plain-bad build adds to each line is
# a second draw in the same timed drawing, a third more time or so for a line's few microseconds.
# Both culprit lines name it.
run pixels plain plain-bad
g3="$t/mesa3"
make_history "$g3" plain plain plain-bad plain-bad
# A third more is a small move: 24 rounds, so that a busy machine's noise does not leave it unknown.
REPEATS=24 bisect b3 pixels "$g3" "$(c "$g3" 0)" "$(c "$g3" 3)" --kind line
[ $rc -eq 0 ] || { show b3; fail "pixel change with --speed: exit $rc"; }
[ "$(grep '^first bad commit:' "$t/b3.out")" = "first bad commit: $(c "$g3" 2) c2: plain-bad (60 primitives)" ] ||
  { show b3; fail "the pixel culprit of c2 not named"; }
grep -qE "^first slower commit: $(c "$g3" 2) c2: plain-bad \(lines, view group A: [0-9.]+x " "$t/b3.out" ||
  { show b3; fail "c2 not named as the first slower commit of lines"; }
grep -q "triangles" "$t/b3.out" && { show b3; fail "--kind line timed triangles"; }

# With paths (-- src), the line skips the commits that touch nothing under src/ (c2, c3, c5).
# Triangles slow down at c3, which the paths leave out: the line names c4, whose git parent c3
# already draws them slowly, so they are unattributed with the bisection without paths over c2
# and c3. Lines slow down at c6, inside the paths, whose git parent c5 is not on the line:
# confirmed beside c5.
path_history() {  # path_history DIR WORD[:src]...: commit cI installs WORD, touches src/ if :src
  local g=$1 i=0 w
  shift
  make_history "$g"
  mkdir -p "$g/src"
  for w in "$@"; do
    echo "${w%:src}" > "$g/driver"
    echo "$i" > "$g/notes"
    [ "$w" = "${w%:src}" ] || echo "$i" > "$g/src/file"
    git -C "$g" add -A
    git -C "$g" commit -q -m "c$i: ${w%:src}"
    i=$((i + 1))
  done
}
run paths plain both-slow
g5="$t/mesa5"
path_history "$g5" plain plain:src plain tris-slow tris-slow:src tris-slow both-slow:src both-slow:src
bisect b5 paths "$g5" "$(c "$g5" 0)" "$(c "$g5" 7)" -- src
[ $rc -eq 1 ] || { show b5; fail "bisect --speed -- src: exit $rc, not 1 (a move unattributed)"; }
grep -qE "^first slower commit: $(c "$g5" 6) c6: both-slow \(lines, view group A: [0-9.]+x " "$t/b5.out" ||
  { show b5; fail "c6 not named as the first slower commit of lines"; }
[ "$(grep -c '^first \(slower\|faster\) commit:' "$t/b5.out")" = 1 ] ||
  { show b5; fail "c4, whose git parent draws the triangles as slowly, named"; }
short() { c "$@" | cut -c1-12; }
grep -qE "^unattributed: drawing time of triangles, view group A \(its git parent $(short "$g5" 3) draws it as $(short "$g5" 4) does \(as bad: [0-9.]+x \[[0-9.]+, [0-9.]+\] the good ref's, [0-9]+% of the way\): the move lies in one of the 2 commits after $(short "$g5" 1) up to the parent, which the paths leave out; without them: " "$t/b5.out" ||
  { show b5; fail "the triangles' move outside the paths not said"; }
without=$(grep "^unattributed: drawing time of triangles" "$t/b5.out")
for part in "--good $(c "$g5" 1) --bad $(c "$g5" 3) " "--kind triangle --out $t/b5/before-$(short "$g5" 4) " "--speed-repeats 8 --speed-primitives 60)"; do
  grep -qF -- "$part" <<<"$without" || { show b5; fail "the bisection without paths lacks '$part'"; }
done
grep -qF -- " -- " <<<"$without" && { show b5; fail "the bisection without paths keeps the paths"; }
/usr/bin/python3 - "$t/b5/bisect.json" "$(c "$g5" 6)" "$(c "$g5" 5)" "$(c "$g5" 1)" "$(c "$g5" 3)" <<'PY' || fail "bisect.json of b5"
import json, sys
j = json.load(open(sys.argv[1]))
[k] = j["speed_culprits"]
assert (k["commit"], k["confirmed_beside"], k["confirmed_beside_note"]) == (sys.argv[2], sys.argv[3], ""), k
assert [(p["kind"], p["place"]) for p in k["parent_places"]] == [("line", "as good")], k
assert [(m["kind"], m["verdict"]) for m in k["moves"]] == [("line", "slower")], k
[u] = j["speed_unattributed"]
assert (u["kind"], u["from"], u["to"]) == ("triangle", sys.argv[4], sys.argv[5]), u
assert f" --good {sys.argv[4]} --bad {sys.argv[5]} " in u["next_command"] and " -- " not in u["next_command"], u
PY
grep -qF "than $(short "$g5" 5), its git parent (the commit before it among those touching the paths given is $(short "$g5" 4))" "$t/b5/bisect.md" ||
  fail "bisect.md does not say c6 was timed beside its git parent"
grep -qE "^\| git parent \| $(short "$g5" 5) \| lines, view group A \| .* \| as good \|$" "$t/b5/bisect.md" ||
  fail "bisect.md does not show where c6's git parent was placed"
named=$(grep -A3 -F "The bisection that names the triangles, view group A move:" "$t/b5/bisect.md")
grep -qF -- "--good $(c "$g5" 1) --bad $(c "$g5" 3) " <<<"$named" || fail "bisect.md lacks the bisection without paths"

# A watch night whose time moved: last night lines-slow, tonight two commits later tris-slow.
printf 'name = "watch-speed"\nseed = 5\nplatforms = ["faulty"]\n[views]\norientations = 1\nfov_deg = [150]\nwindows = [256]\nnear = 0.01\nfar = 10.0\n[primitives]\npoints = 0\nlines = 0\ntriangles = 60\n' > "$t/nightly.toml"
up="$t/upstream"
make_history "$up" lines-slow
git clone -q "$up" "$t/watched"
night() {  # night N
  set +e
  "$ra" watch "$t/watched" --experiment "$t/nightly.toml" --state "$t/state" --build-command "$cmd" \
    --jobs 2 --no-pictures --speed --speed-repeats 8 --speed-primitives 60 --keep-nights 1 \
    >"$t/night$1.out" 2>"$t/night$1.err"
  rc=$?
  set -e
}
night 1
[ $rc -eq 0 ] || { show night1; fail "night 1: exit $rc"; }
for d in lines-slow both-slow; do
  echo "$d" > "$up/driver"
  git -C "$up" commit -q --allow-empty -am "c$(git -C "$up" rev-list --count HEAD): $d"
done
night 2
[ $rc -eq 1 ] || { show night2; fail "night 2 (time moved): exit $rc"; }
grep -qF "night: changed: no primitive changed; drawing time of 1 group moved, 1 commit(s) named" "$t/night2.out" ||
  { show night2; fail "night 2 does not say its time moved"; }
grep -qE "^first slower commit: $(c "$up" 2) c2: both-slow \(faulty: triangles, view group A: [0-9.]+x " "$t/night2.out" ||
  { show night2; fail "night 2 does not name c2 as the first slower commit"; }
grep -q "culprit: first slower commit: $(c "$up" 2)" <("$ra" history --db "$t/state/history.sqlite" 2>&1) ||
  fail "the history does not keep night 2's slower commit"
# --keep-nights 1: night 1's folder removed once night 2 was recorded, tonight's kept.
[ "$(ls "$t/state/nights")" = "$(basename "$(dirname "$(sed -n 's/^details: //p' "$t/night2.out")")")" ] ||
  fail "--keep-nights 1 left $(ls "$t/state/nights" | tr '\n' ' ')"
echo "bisect-speed-test: ok"
