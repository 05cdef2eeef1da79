#!/usr/bin/env bash
# `renderaudit report RUN --upgrade BUILD` (the driver upgrade report, triage/upgrade_report.h) on a
# real run of stand-in drivers (tests/scripts/bisect-fixture.sh), no Mesa build (ctest upgrade_report): the installed driver `faulty` (llvmpipe) against two builds drawn in
# one run, faulty@backports (a wild pixel on every line) and faulty@source (on the even lines
# only), audited into the folders scripts/driver-upgrade.sh uses (audit-P, audit-P-source):
#   - the source part's per-platform table shows the source audit's counts, not the backports ones,
#     and an audit of another pair in the folder is refused (exit 2, the file named);
#   - the summary's counts per kind and view group add up to the audit's own count of changed
#     primitives (one comparison, the audit's);
#   - six view groups (3 fields of view x 2 windows) are named A-F, no crash past four;
#   - the `renderaudit show` line pastes as one word per argument though the run folder is named
#     like a command substitution, and runs nothing;
#   - every picture the report names was drawn (each side `show --against` the other, the other
#     drawn with a driver build in a child process);
#   - the [builds.source] table driver-upgrade.sh appends (scripts/build_table.py) keeps a source
#     path and ref with newlines, quotes and TOML of their own inside their string and comment;
#   - drawing time: faulty@backports also draws 3 times as long ([faults] slowdown = 2) and its
#     audit judges time as driver-upgrade.sh's do (--speed --speed-warn-only, 3 rounds: about 2 s);
#     the summary carries its verdicts (slower, never faster or the same) and page 1 says so; the
#     source audit, not timed, leaves `speed` out and page 1 without a word of time.
# Usage: tests/scripts/upgrade-report-test.sh BUILD_DIR
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
t=$(mktemp -d /tmp/renderaudit-upgrade-report-XXXXXX)
trap '[ -n "${KEEP:-}" ] || rm -rf "$t"' EXIT
. "$(dirname "$0")/bisect-fixture.sh"
scripts="$(cd "$(dirname "$0")/../../scripts" && pwd)"

run="$t/out \$(touch $t/PWNED) it's"
# the bad driver, also drawing 3 times as long
mkdir -p "$t/drivers/bad-slow"
printf 'slowdown = 2\n' | cat "$t/drivers/bad/faults.toml" - > "$t/drivers/bad-slow/faults.toml"
cat > "$t/upgrade.toml" <<EOT
name = "upgrade-report-test"
seed = 7
platforms = ["faulty", "faulty@backports", "faulty@source"]
[faults]
base = "osmesa-llvmpipe"
[builds.backports]
dir = "$t/drivers/bad-slow"
[builds.source]
dir = "$t/drivers/neither"
[views]
orientations = 1
fov_deg = [30, 60, 90]
windows = [64, 128]
near = 0.01
far = 10.0
[primitives]
points = 0
lines = 8
triangles = 0
EOT
"$ra" run "$t/upgrade.toml" --out "$run" --jobs 2 >/dev/null 2>"$t/run.log" || { cat "$t/run.log"; fail "run"; }
for b in backports source; do
  suffix=$([ $b = backports ] || echo "-$b")
  speed=()
  [ $b = source ] || speed=(--speed --speed-warn-only --speed-repeats 3)
  set +e
  "$ra" audit "$run" --between faulty "faulty@$b" --no-history "${speed[@]}" \
    --out "$run/audit-faulty$suffix" >"$t/audit-$b.log" 2>&1
  rc=$?
  set -e
  [ $rc -le 1 ] || { cat "$t/audit-$b.log"; fail "audit of faulty@$b exited $rc"; }
done
changed() {  # changed AUDIT_FOLDER: the audit's count of changed primitives
  /usr/bin/python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["counts"]["changed"])' "$1/audit.json"
}
backports_changed=$(changed "$run/audit-faulty")
source_changed=$(changed "$run/audit-faulty-source")
[ "$backports_changed" != "$source_changed" ] ||
  fail "the two builds changed as many primitives ($source_changed): the test proves nothing"

# The source part, as driver-upgrade.sh writes it.
"$ra" report "$run" --upgrade source --audit-suffix -source --platforms faulty >"$t/source.md" 2>"$t/source.err" ||
  { cat "$t/source.err"; fail "report --upgrade (source) failed"; }
row=$(grep -m1 '^| faulty | ' "$t/source.md")
[ "$(cut -d'|' -f6 <<<"$row" | tr -d ' ')" = "$source_changed" ] ||
  { echo "$row"; fail "the source part's table does not show the source audit's $source_changed changed (backports: $backports_changed)"; }
for g in A B C D E F; do
  grep -q "^| line | $g | " "$t/source.md" || fail "view group $g is not in the per-kind table"
done
# An audit folder of another pair is refused, naming the file.
set +e
"$ra" report "$run" --upgrade source --platforms faulty >"$t/wrong.md" 2>"$t/wrong.err"
rc=$?
set -e
[ $rc = 2 ] && grep -qF "$run/audit-faulty/audit.json: 'pairs' does not compare faulty with faulty@source" "$t/wrong.err" ||
  { cat "$t/wrong.err"; fail "another pair's audit: exit $rc"; }

# The `renderaudit show` line: the words that ran, nothing run.
"$ra" report "$run" --upgrade backports --platforms faulty >"$t/backports.md" 2>"$t/backports.err" ||
  { cat "$t/backports.err"; fail "report --upgrade (backports) failed"; }

# The pictures: each one the report names is there, a pair per finding.
/usr/bin/python3 - "$run" "$t/backports.md" <<'EOP' || fail "the report's pictures (above)"
import os, re, sys
run, md = sys.argv[1:]
pictures = re.findall(r"!\[[^]]*\]\(([^)]+\.png)\)", open(md).read())
assert pictures and len(pictures) % 2 == 0, pictures
missing = [p for p in pictures if not os.path.isfile(os.path.join(run, p))]
assert not missing, f"pictures not drawn: {missing}"
EOP

# Drawing time: the timed audit's verdicts in the summary and on page 1, none from the untimed one.
/usr/bin/python3 - "$run" "$t/backports.md" "$t/source.md" <<'EOP' || fail "the drawing times of the summary or page 1 (above)"
import json, re, sys
run, backports_md, source_md = sys.argv[1:]
speed = json.load(open(f"{run}/upgrade-summary-backports.json"))["pairs"][0].get("speed")
assert speed is not None, "the timed audit's pair has no 'speed'"
assert sorted(s["group"] for s in speed) == list("ABCDEF"), speed
for s in speed:
    assert set(s) == {"kind", "group", "ratio", "low", "high", "verdict"}, s
    # 3 times as long is never faster or the same; under heavy load a group may stay unknown
    assert s["kind"] == "line" and s["verdict"] in ("slower", "unknown"), s
slower = [s for s in speed if s["verdict"] == "slower"]
assert slower, f"a driver 3 times as slow is slower in no group: {speed}"
page1 = open(backports_md).read().splitlines()[2]
assert re.search(r"\. faulty \S+ draws the lines [0-9-]+% slower \(95%: [0-9-]+%\)", page1), page1
assert ("could not be judged" in page1) == (len(slower) < len(speed)), page1
# the counts per kind and view group are the audit's own: they add up to its count of changed
for build, folder in (("backports", "audit-faulty"), ("source", "audit-faulty-source")):
    pair = json.load(open(f"{run}/upgrade-summary-{build}.json"))["pairs"][0]
    audit = json.load(open(f"{run}/{folder}/audit.json"))["counts"]
    assert sum(s["changed"] for s in pair["strata"]) == audit["changed"], (build, pair, audit)
    assert sum(s["compared"] for s in pair["strata"]) == audit["compared"], (build, pair, audit)
source = json.load(open(f"{run}/upgrade-summary-source.json"))["pairs"][0]
assert "speed" not in source, source
page1 = open(source_md).read().splitlines()[2]
assert not re.search(r"(faster|slower) \(95%|drawing time", page1), page1
EOP
show=$(grep -o -m1 '`renderaudit show [^`]*`' "$t/backports.md")
show=${show%%$'\n'*}
show=${show//\`/}
[ -n "$show" ] || fail "no renderaudit show line in the report"
mkdir -p "$t/stub"
printf '#!/bin/sh\nprintf "%%s\\0" "$@" > "$STUB_ARGS"\n' > "$t/stub/renderaudit"
chmod +x "$t/stub/renderaudit"
(cd "$t" && STUB_ARGS="$t/show.args" PATH="$t/stub:$PATH" bash -c "$show") || fail "the show line does not run in bash: $show"
[ ! -e "$t/PWNED" ] || fail "pasting the show line ran the run folder's \$(touch ...)"
[ "$(tr '\0' '\n' <"$t/show.args" | sed -n 2p)" = "$run" ] || fail "the show line's run folder is not one word: $show"
# The [builds.source] table driver-upgrade.sh appends: a source path and a ref with a newline, a
# quote, a backslash and TOML of their own read back as themselves, adding no key or table.
hostile=$'/srv/mesa "x"\\\nrun.shard_size = 7 #'
ref=$'main\n[bogus]'
{ cat "$t/upgrade.toml"; /usr/bin/python3 "$scripts/build_table.py" source2 "$hostile" \
    "renderaudit builds build $hostile --ref $ref"; } > "$t/with-source.toml"
/usr/bin/python3 - "$t/with-source.toml" "$hostile" <<'EOP' || fail "build_table.py wrote TOML that reads back otherwise"
import sys, tomllib
doc = tomllib.load(open(sys.argv[1], "rb"))
assert doc["builds"]["source2"] == {"dir": sys.argv[2]}, doc["builds"]
assert "bogus" not in doc and "shard_size" not in doc.get("run", {}), doc
EOP
grep -q 'scripts/build_table.py" source "$source_dir"' "$scripts/driver-upgrade.sh" ||
  fail "driver-upgrade.sh does not write its [builds.source] table with build_table.py"
echo "upgrade-report-test: the source part, six view groups, the audit's counts, the show line, the pictures, the build table, drawing times checked"
echo "1 passed, 0 failed"
