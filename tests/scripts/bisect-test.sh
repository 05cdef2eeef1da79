#!/usr/bin/env bash
# `renderaudit bisect` end to end with real drawing and no compiler (ctest bisect_faulty): stand-in
# driver builds and git histories (tests/scripts/bisect-fixture.sh). History g: c0-c3 good, c4 bad,
# c5 neither (the odd lines back to good), c6 bad, c7 bad, c8 good again, c9 broken, c10 bad.
# Checked: every change named to its commit, also a primitive changed three times; two culprits of
# disjoint primitives; a change next to a build that fails (candidates, exit 1); a change undone
# inside the range (not seen: the documented limit); refs that draw alike; a resumed
# multi-primitive bisection; other inputs refused; the report's parts.
# Usage: tests/scripts/bisect-test.sh BUILD_DIR
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
t=$(mktemp -d /tmp/renderaudit-bisect-test-XXXXXX)
trap '[ -n "${KEEP:-}" ] || rm -rf "$t"' EXIT
. "$(dirname "$0")/bisect-fixture.sh"
make_run
g="$t/mesa"
make_history "$g" good good good good bad neither bad bad good broken bad

bisect() {  # bisect NAME GOOD BAD [options]: exit code in $rc
  local name=$1 good=$2 bad=$3
  shift 3
  set +e
  "$ra" bisect "$t/run" --between faulty@good faulty@bad --source "$g" --good "$good" \
    --bad "$bad" --build-command "$cmd" --out "$t/$name" --jobs 2 "$@" \
    >"$t/$name.out" 2>"$t/$name.err"
  rc=$?
  set -e
}
# culprits NAME: "cI:N ..." from the stdout lines, in order.
culprits() {
  local out
  out=$(cat "$t/$1.out")
  while read -r _ _ _ hash subject _ n _; do
    printf '%s:%s ' "${subject%:}" "${n#(}"
  done <<< "$(grep '^first bad commit: ' <<< "$out")"
}

# Every change named: the even lines change at c4; the odd ones at c4, back at c5, again at c6.
bisect b1 "$(c "$g" 0)" "$(c "$g" 7)" --max-primitives 6
[ $rc -eq 0 ] || { cat "$t/b1.out" "$t/b1.err"; fail "bisect exited $rc"; }
[ "$(culprits b1)" = "c4:6 c5:3 c6:3 " ] || { cat "$t/b1.out"; fail "culprits of c0..c7: $(culprits b1)"; }
[ "$(tail -1 "$t/b1.out")" = "first bad commit: $(c "$g" 6) c6: bad (3 primitives)" ] ||
  fail "stdout does not end with one line per culprit"
[ "$(git -C "$g" symbolic-ref --short HEAD)" = main ] || fail "the tree was not returned to its branch"
[ ! -e "$g/.git/BISECT_START" ] || fail "a git bisect was left behind"
/usr/bin/python3 - "$t/b1/bisect.json" "$(c "$g" 3)" "$(c "$g" 4)" <<'PY' || fail "bisect.json"
import json, sys
j = json.load(open(sys.argv[1]))
assert j["complete"] and len(j["selection"]) == 6 and not j["unattributed"], j
first = j["culprits"][0]
assert first["commit"] == sys.argv[3] and first["previous"] == sys.argv[2], first
# The good driver lights each line's pixels, the bad one a wild pixel more.
for p in first["primitives"]:
    assert p["pixels_after"] == p["pixels_before"] + 1, p
assert sum(len(c["primitives"]) for c in j["culprits"]) == 12
# A binary search of 7 commits, no commit built twice.
commits = [s["commit"] for s in j["steps"]]
assert len(commits) == len(set(commits)) <= 4, commits
PY
for part in "3 culprit commits" "## 1. " "c4: bad" "**What changed.**" "## The bisection" "## Repeat it" "renderaudit bisect"; do
  grep -qF -- "$part" "$t/b1/bisect.md" || fail "bisect.md lacks '$part'"
done

# Two culprits of disjoint primitives: the even lines at c2, the odd ones at c4.
g2="$t/mesa2"
make_history "$g2" good good neither neither bad
g_saved=$g; g=$g2
bisect b7 "$(c "$g" 0)" "$(c "$g" 4)" --max-primitives 6 --no-pictures
g=$g_saved
[ $rc -eq 0 ] && [ "$(culprits b7)" = "c2:3 c4:3 " ] || { cat "$t/b7.out" "$t/b7.err"; fail "two culprits: $(culprits b7)"; }

# A change undone inside the range: c0..c10 passes c8 (good again) and c9 (broken); the builds at
# c7 and c10 both draw the bad pixels, so c8 and c10's changes are never seen (the ends decide
# what is looked for), and the answer is that of c0..c7.
bisect b8 "$(c "$g" 0)" "$(c "$g" 10)" --max-primitives 6 --no-pictures
[ $rc -eq 0 ] && [ "$(culprits b8)" = "c4:6 c5:3 c6:3 " ] || { cat "$t/b8.out" "$t/b8.err"; fail "undone change: $(culprits b8)"; }
grep -q "$(c "$g" 8 | cut -c1-12)" "$t/b8/bisect.md" && fail "c8 was built although nothing asks for it"

# The report's "Repeat it" command pastes into a shell as the very command that ran: every value
# one word, though the source folder is named like a command substitution with a quote, the output
# folder holds a line break and the build command a quote.
hs="$t/src dir \$(touch $t/PWNED) it's"
git clone -q "$g" "$hs"
hout="$t/b6 out
line"
hcmd="$cmd; : \"it's\""
"$ra" bisect "$t/run" --between faulty@good faulty@bad --source "$hs" --good "$(c "$g" 3)" \
  --bad "$(c "$g" 6)" --build-command "$hcmd" --max-primitives 6 --out "$hout" --no-pictures \
  >"$t/b6.out" 2>"$t/b6.err" || { cat "$t/b6.out" "$t/b6.err"; fail "bisect of a source folder with a hostile name"; }
repeat=$(awk '/^## Repeat it$/ {r = 1; next} r && /^```sh$/ {b = 1; next} b && /^```$/ {exit} b' "$hout/bisect.md")
# It names this program as it runs here (the build folder's is not on PATH), then a stand-in
# takes its place to record the words it is given.
[ "${repeat%% bisect *}" = "$(realpath "$ra")" ] ||
  fail "the Repeat it command does not name the program that ran: $repeat"
repeat="renderaudit bisect ${repeat#* bisect }"
mkdir -p "$t/stub"
printf '#!/bin/sh\nprintf "%%s\\0" "$@" > "$STUB_ARGS"\n' > "$t/stub/renderaudit"
chmod +x "$t/stub/renderaudit"
STUB_ARGS="$t/repeat.args" PATH="$t/stub:$PATH" bash -c "$repeat" ||
  fail "the Repeat it command does not run in bash: $repeat"
[ ! -e "$t/PWNED" ] || fail "the Repeat it command ran the source folder's \$(touch ...)"
cmp -s "$t/repeat.args" <(printf '%s\0' bisect "$t/run" --between faulty@good faulty@bad \
  --source "$hs" --good "$(c "$g" 3)" --bad "$(c "$g" 6)" --max-primitives 6 --out "$hout" \
  --build-command "$hcmd" --no-pictures) || fail "the Repeat it command is not the command that ran: $repeat"

# Refs that draw alike: nothing to bisect.
bisect b3 "$(c "$g" 1)" "$(c "$g" 3)" --no-pictures
[ $rc -eq 2 ] || fail "c1..c3 (both good) should be refused, exit $rc"
grep -q "draw all 40 selected primitives alike on faulty" "$t/b3.err" || { cat "$t/b3.err"; fail "refs drawing alike not said"; }

# A build that fails next to the change: c8..c10, only c9 (broken) between.
bisect b4 "$(c "$g" 8)" "$(c "$g" 10)" --max-primitives 6 --no-pictures
[ $rc -eq 1 ] || { cat "$t/b4.out" "$t/b4.err"; fail "only a failed build between: exit 1 expected, got $rc"; }
grep -q "skipped for every primitive: build failed: builds build: the build command step failed" "$t/b4.err" &&
  grep -q "^cannot build broken" "$t/b4.err" || { cat "$t/b4.err"; fail "the failed build is not named"; }
[ "$(grep -c "^unattributed: .* (one of: $(c "$g" 9 | cut -c1-12) $(c "$g" 10 | cut -c1-12))" "$t/b4.out")" = 6 ] ||
  { cat "$t/b4.out"; fail "candidates"; }
grep -q "## Unattributed" "$t/b4/bisect.md" || fail "the report does not list the unattributed changes"

# Resume: the first bisection's later steps forgotten, the same command goes on from there. (The
# file edited is written as one of version 2, from before the seal, which is read field by field.)
/usr/bin/python3 - "$t/b1/bisect.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
j["steps"] = j["steps"][:1]
del j["seal"]
j["schema_version"] = 2
json.dump(j, open(sys.argv[1], "w"))
PY
bisect b1 "$(c "$g" 0)" "$(c "$g" 7)" --max-primitives 6 --no-pictures
[ $rc -eq 0 ] || { cat "$t/b1.err"; fail "resume"; }
grep -q "resuming .*: 1 steps built" "$t/b1.err" || { cat "$t/b1.err"; fail "did not resume"; }
[ "$(culprits b1)" = "c4:6 c5:3 c6:3 " ] || fail "resumed bisection: $(culprits b1)"
grep -q "reused build" "$t/b1.err" || fail "resumed bisection rebuilt what was cached"
# Other inputs into the same folder are refused.
bisect b1 "$(c "$g" 1)" "$(c "$g" 7)" --max-primitives 6
[ $rc -eq 2 ] || fail "other inputs accepted"
grep -q "holds a bisection of other inputs ('good' differs)" "$t/b1.err" || { cat "$t/b1.err"; fail "other inputs: message"; }
echo "bisect-test: 7 bisections checked"
echo "1 passed, 0 failed"
