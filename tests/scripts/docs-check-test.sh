#!/usr/bin/env bash
# The test of the docs check (ctest docs_check_fixture): on a made-up tree whose README and docs
# quote a stale test count, a stale figure count of the quick experiment and a command table that
# misses a command, names one that does not exist and leaves out a subcommand, docs-check.sh must
# fail naming each file and line; on the same tree with the numbers right it must pass. The build
# folder is a stand-in: a CTestTestfile.cmake of three tests and a `renderaudit` script that prints
# a help text and a figure plan.
# Usage: tests/scripts/docs-check-test.sh
set -uo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
t=$(mktemp -d /tmp/renderaudit-docs-check-test-XXXXXX)
trap '[ -n "${KEEP:-}" ] || rm -rf "$t"' EXIT
bad=0
fail() { echo "docs-check-test: FAIL: $*" >&2; bad=1; }

mkdir -p "$t/build" "$t/tree/docs" "$t/tree/experiments" "$t/run"
printf 'add_test(one "true")\nadd_test(two "true")\nadd_test(three "true")\n' \
  > "$t/build/CTestTestfile.cmake"
cat > "$t/build/renderaudit" <<'PROGRAM'
#!/bin/sh
case "$1 $2" in
  "--help "*) printf 'Usage: renderaudit SUBCOMMAND\n\nSubcommands:\n  run    Render\n            and measure\n  builds  Driver builds\n  plot   Figures\n\n' ;;
  "builds --help") printf 'Subcommands:\n  fetch  Fetch\n  remove  Remove\n' ;;
  "run --help"|"plot --help") printf 'Usage: renderaudit %s DIR\n' "$1" ;;
  "plot "*) printf 'a  A\nb  B\n7 figures planned for %s (nothing drawn)\n' "$2" ;;
  *) exit 2 ;;
esac
PROGRAM
chmod +x "$t/build/renderaudit"
echo 'name = "quick"' > "$t/tree/experiments/quick.toml"
echo 'name = "quick-egl"' > "$t/tree/experiments/quick-egl.toml"
cp "$t/tree/experiments/quick.toml" "$t/run/experiment.toml"

write_tree() {  # TESTS FIGURES BUILDS_ROW EXTRA_ROW
  cat > "$t/tree/README.md" <<README
# made up

| target | what it does |
| --- | --- |
| \`make test\` | the whole suite ($1 tests) |

## Commands

| command | what it does |
| --- | --- |
| \`renderaudit run X\` | render |
| $3 | builds |
$4
## Documentation
README
  printf '# Figures\n\nThe quick experiment'"'"'s %s figures take a second.\n' "$2" \
    > "$t/tree/docs/figures.md"
}

write_tree 704 70 '`renderaudit builds fetch SUITE`' '| `renderaudit timings X` | none |'
out=$("$here/scripts/docs-check.sh" --root "$t/tree" "$t/build" "$t/run" 2>&1)
rc=$?
[ "$rc" = 1 ] || fail "stale docs: exit $rc, expected 1"
expect=(
  "docs-check: README.md:5: says 704 tests; \`ctest -N\` lists 3"
  "docs-check: README.md:9: the command table has no row for \`renderaudit plot\`"
  "docs-check: README.md:12: the row of \`renderaudit builds\` does not name its subcommand remove"
  "docs-check: README.md:13: \`renderaudit timings\` is not a command of renderaudit --help"
  "docs-check: docs/figures.md:3: says the quick experiment has 70 figures; \`renderaudit plot $t/run --list\` plans 7"
  "docs-check: 5 stale number(s) or name(s)"
)
for line in "${expect[@]}"; do
  grep -qF -- "$line" <<<"$out" || fail "missing: $line"
done

write_tree 3 7 '`renderaudit builds fetch SUITE`, `builds remove NAME`' '| `renderaudit plot DIR` | figures |'
out2=$("$here/scripts/docs-check.sh" --root "$t/tree" "$t/build" "$t/run" 2>&1)
rc=$?
[ "$rc" = 0 ] || fail "docs that agree: exit $rc: $out2"
grep -qF "docs-check: the docs agree with the commands: 3 tests, 3 commands, 7 figures" <<<"$out2" \
  || fail "no agreement line: $out2"

if [ "$bad" != 0 ]; then echo "--- the check printed:"; echo "$out"; exit 1; fi
echo "docs-check-test: a stale test count, figure count and command table named by file and line"
