#!/usr/bin/env bash
# `renderaudit bisect` end to end with real drawing and no compiler (ctest bisect_faulty): a git
# history made here whose commits each name one of four prebuilt "drivers", and a build command
# that only copies the named one into place. The drivers are the `faulty` test platform over the
# installed Mesa llvmpipe (osmesa-llvmpipe): `faulty@BUILD` draws with BUILD/faults.toml, so
#   good:    llvmpipe as it is;
#   bad:     llvmpipe with one wild pixel far from every primitive (wild_pixel);
#   neither: llvmpipe with the wild pixels of even primitives only (half like each side);
#   broken:  the build command fails.
# History: c0-c3 good, c4 bad (the first bad commit), c5 neither, c6 bad, c7 bad, c8 good again,
# c9 broken, c10 bad. Checked: the first bad commit and its parent's and its pixels, a step whose
# pixels are neither side's, a build that fails next to the change (no single first bad commit),
# refs that draw alike, a resumed bisection, other inputs refused, and the report's parts.
# Usage: scripts/bisect-test.sh BUILD_DIR
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
ra="$build/renderaudit"
t=$(mktemp -d /tmp/renderaudit-bisect-test-XXXXXX)
trap '[ -n "${KEEP:-}" ] || rm -rf "$t"' EXIT
fail() { echo "bisect-test: FAIL: $*" >&2; exit 1; }

mkdir -p "$t/drivers"/{good,bad,neither}
printf '[faults]\nbase = "osmesa-llvmpipe"\n' > "$t/drivers/good/faults.toml"
printf '[faults]\nbase = "osmesa-llvmpipe"\nwild_pixel = [%s]\n' "$(seq -s, 0 39)" > "$t/drivers/bad/faults.toml"
printf '[faults]\nbase = "osmesa-llvmpipe"\nwild_pixel = [%s]\n' "$(seq -s, 0 2 39)" > "$t/drivers/neither/faults.toml"

cat > "$t/exp.toml" <<EOF
name = "bisect-test"
seed = 7
platforms = ["faulty@good", "faulty@bad"]
[builds.good]
dir = "$t/drivers/good"
[builds.bad]
dir = "$t/drivers/bad"
[views]
orientations = 1
fov_deg = [30]
windows = [128]
near = 0.01
far = 10.0
[primitives]
points = 0
lines = 40
triangles = 0
EOF
"$ra" run "$t/exp.toml" --out "$t/run" --jobs 2 >/dev/null 2>"$t/run.log" || { cat "$t/run.log"; fail "run"; }

# The driver history.
g="$t/mesa"
mkdir -p "$g"
git -C "$g" init -q
git -C "$g" config user.email test@example.invalid
git -C "$g" config user.name test
i=0
for d in good good good good bad neither bad bad good broken bad; do
  echo "$d" > "$g/driver"
  git -C "$g" add driver
  git -C "$g" commit -q --allow-empty -m "c$i: $d"
  i=$((i + 1))
done
c() { git -C "$g" rev-parse ":/^c$1:"; }
cmd='d=$(cat driver); [ "$d" != broken ] || { echo "cannot build $d" >&2; exit 1; }; cp '"$t"'/drivers/$d/faults.toml "$RENDERAUDIT_BUILD_PREFIX"/'
export RENDERAUDIT_BUILD_CACHE="$t/cache"

set +e
"$ra" bisect "$t/run" --between faulty@good faulty@bad --source "$g" --good "$(c 0)" \
  --bad "$(c 7)" --build-command "$cmd" --max-primitives 6 --out "$t/b1" --jobs 2 \
  >"$t/b1.out" 2>"$t/b1.err"
rc=$?
set -e
[ $rc -eq 0 ] || { cat "$t/b1.out" "$t/b1.err"; fail "bisect exited $rc"; }
grep -q "^first bad commit: $(c 4) c4: bad" "$t/b1.out" || { cat "$t/b1.out" "$t/b1.err"; fail "first bad commit is not c4"; }
grep -q "^parent: $(c 3)" "$t/b1.out" || fail "parent is not c3"
[ "$(git -C "$g" rev-parse HEAD)" = "$(c 10)" ] || fail "the tree was not returned to where it was"
[ ! -e "$g/.git/BISECT_START" ] || fail "git bisect was not reset"
/usr/bin/python3 - "$t/b1/bisect.json" "$(c 2)" "$(c 5)" <<'EOF' || fail "bisect.json"
import json, sys
j = json.load(open(sys.argv[1]))
steps = {s["commit"]: s for s in j["steps"]}
assert j["found"] and j["first_bad"] and len(j["selection"]) == 6, j["selection"]
assert j["confirm"]["parent"]["verdict"] == "good", j["confirm"]["parent"]
assert j["confirm"]["first bad"]["verdict"] == "bad"
for s in j["steps"]:
    assert s["verdict"] in ("good", "bad", "skip")
    if s["verdict"] == "skip":
        assert s["reason"].startswith(("build failed", "pixels are neither")), s["reason"]
# Every selected primitive drawn by the parent and the first bad commit: the bad driver lights
# the good one's pixels and one wild pixel more.
good = j["confirm"]["parent"]["drawing"]["primitives"]
bad = j["confirm"]["first bad"]["drawing"]["primitives"]
assert len(good) == 6 and good.keys() == bad.keys()
for k in good:
    assert bad[k]["pixels"] == good[k]["pixels"] + 1, (k, good[k], bad[k])
    assert bad[k]["pixel_hash"] != good[k]["pixel_hash"]
print("steps:", [(s["commit"][:7], s["verdict"]) for s in j["steps"]])
EOF
for part in "What is wrong" "## Versions" "## The first bad commit" "c4: bad" "## Every selected primitive" "## The bisection" "## Repeat it" "renderaudit bisect"; do
  grep -qF "$part" "$t/b1/bisect.md" || fail "bisect.md lacks '$part'"
done

# A step that draws neither side's pixels: c3..c6 passes through c5.
"$ra" bisect "$t/run" --between faulty@good faulty@bad --source "$g" --good "$(c 3)" \
  --bad "$(c 6)" --build-command "$cmd" --max-primitives 6 --out "$t/b2" --no-pictures \
  >"$t/b2.out" 2>"$t/b2.err" || { cat "$t/b2.out" "$t/b2.err"; fail "bisect c3..c6"; }
grep -q "^first bad commit: $(c 4)" "$t/b2.out" || fail "c3..c6: first bad commit is not c4"
grep -q "skip: pixels are neither: 3 like the good ref, 3 like the bad ref, 0 like neither" "$t/b2.err" || { cat "$t/b2.err"; fail "c5 was not skipped as drawing neither side"; }
# The report's "Repeat it" command pastes into a shell as the very command that ran: every value
# one word, though the source folder is named like a command substitution with a quote, the output
# folder holds a line break and the build command a quote.
hs="$t/src dir \$(touch $t/PWNED) it's"
git clone -q "$g" "$hs"
hout="$t/b6 out
line"
hcmd="$cmd; : \"it's\""
"$ra" bisect "$t/run" --between faulty@good faulty@bad --source "$hs" --good "$(c 3)" \
  --bad "$(c 6)" --build-command "$hcmd" --max-primitives 6 --out "$hout" --no-pictures \
  >"$t/b6.out" 2>"$t/b6.err" || { cat "$t/b6.out" "$t/b6.err"; fail "bisect of a source folder with a hostile name"; }
repeat=$(awk '/^## Repeat it$/ {r = 1; next} r && /^```sh$/ {b = 1; next} b && /^```$/ {exit} b' "$hout/bisect.md")
mkdir -p "$t/stub"
printf '#!/bin/sh\nprintf "%%s\\0" "$@" > "$STUB_ARGS"\n' > "$t/stub/renderaudit"
chmod +x "$t/stub/renderaudit"
STUB_ARGS="$t/repeat.args" PATH="$t/stub:$PATH" bash -c "$repeat" ||
  fail "the Repeat it command does not run in bash: $repeat"
[ ! -e "$t/PWNED" ] || fail "the Repeat it command ran the source folder's \$(touch ...)"
cmp -s "$t/repeat.args" <(printf '%s\0' bisect "$t/run" --between faulty@good faulty@bad \
  --source "$hs" --good "$(c 3)" --bad "$(c 6)" --max-primitives 6 --out "$hout" \
  --build-command "$hcmd") || fail "the Repeat it command is not the command that ran: $repeat"
# Refs that draw alike: nothing to bisect.
"$ra" bisect "$t/run" --between faulty@good faulty@bad --source "$g" --good "$(c 1)" \
  --bad "$(c 3)" --build-command "$cmd" --out "$t/b3" --no-pictures >"$t/b3.out" 2>"$t/b3.err" && \
  fail "c1..c3 (both good) should find no change"
grep -q "draw all 24 selected primitives alike on faulty" "$t/b3.err" || { cat "$t/b3.err"; fail "refs drawing alike not said"; }
# A build that fails next to the change: c8..c10, only c9 (broken) between.
set +e
"$ra" bisect "$t/run" --between faulty@good faulty@bad --source "$g" --good "$(c 8)" \
  --bad "$(c 10)" --build-command "$cmd" --max-primitives 6 --out "$t/b4" --no-pictures \
  >"$t/b4.out" 2>"$t/b4.err"
rc=$?
set -e
[ $rc -eq 1 ] || { cat "$t/b4.out" "$t/b4.err"; fail "only skipped commits left: exit 1 expected, got $rc"; }
grep -q "skip: build failed: builds build: the build command step failed" "$t/b4.err" &&
  grep -q "^cannot build broken" "$t/b4.err" || { cat "$t/b4.err"; fail "the failed build is not named"; }
grep -q "skipped commits leave 2 candidates" "$t/b4.out" || { cat "$t/b4.out"; fail "candidates"; }
grep -q "$(c 9)" "$t/b4/bisect.md" || fail "the report does not list the candidates"

# Resume: the first bisection's last step forgotten, the same command goes on from there.
/usr/bin/python3 - "$t/b1/bisect.json" <<'EOF'
import json, sys
j = json.load(open(sys.argv[1]))
j["steps"] = j["steps"][:1]
j["confirm"] = {}
json.dump(j, open(sys.argv[1], "w"))
EOF
"$ra" bisect "$t/run" --between faulty@good faulty@bad --source "$g" --good "$(c 0)" \
  --bad "$(c 7)" --build-command "$cmd" --max-primitives 6 --out "$t/b1" --no-pictures \
  >"$t/b5.out" 2>"$t/b5.err" || { cat "$t/b5.err"; fail "resume"; }
grep -q "resuming .*: 1 steps judged" "$t/b5.err" || { cat "$t/b5.err"; fail "did not resume"; }
grep -q "^first bad commit: $(c 4)" "$t/b5.out" || fail "resumed bisection: first bad commit is not c4"
grep -q "reused build" "$t/b5.err" || fail "resumed bisection rebuilt what was cached"
# Other inputs into the same folder are refused.
"$ra" bisect "$t/run" --between faulty@good faulty@bad --source "$g" --good "$(c 1)" \
  --bad "$(c 7)" --build-command "$cmd" --max-primitives 6 --out "$t/b1" >/dev/null 2>"$t/b6.err" && fail "other inputs accepted"
grep -q "holds a bisection of other inputs ('good' differs)" "$t/b6.err" || { cat "$t/b6.err"; fail "other inputs: message"; }
echo "bisect-test: 6 bisections checked"
echo "1 passed, 0 failed"
