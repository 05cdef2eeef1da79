#!/usr/bin/env bash
# The stand-in histories of tests/scripts/bisect-fixture.sh bisected with --ways 1 and --ways 3, side by
# side: rounds, builds, builds cancelled, wall time and building time, as a markdown table for
# docs/benchmarks.md. Each bisection starts from an empty build cache. SLEEP (default 10) is each
# stand-in build's cost in seconds: a sleep, which takes no core, so the builds of a round overlap
# fully (the case of enough cores per build: a big node or a cluster); SLEEP=0 leaves the
# bisection's own costs (worktrees, processes, drawing).
# Usage: scripts/bisect-ways-bench.sh BUILD_DIR [SLEEP...]
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
shift || true
sleeps=("${@:-10}")
[ $# -gt 0 ] || sleeps=(0 10)
t=$(mktemp -d /tmp/renderaudit-bisect-ways-bench-XXXXXX)
trap '[ -n "${KEEP:-}" ] || rm -rf "$t"' EXIT
. "$(dirname "$0")/../tests/scripts/bisect-fixture.sh"
make_run

make_line() {  # NAME WORD... with runs "WORD*N"
  local name=$1 w n words=()
  shift
  for w in "$@"; do n=${w#*\*}; w=${w%\*"$n"}; for _ in $(seq "$n"); do words+=("$w"); done; done
  make_history "$t/$name" "${words[@]}"
}
make_line one 'good*33' 'bad*32'                     # one culprit (c33) in 64 commits
make_line two 'good*10' 'neither*10' 'bad*5'         # two culprits (c10, c20) in 24 commits
make_line several 'good*4' 'bad*1' 'neither*1' 'bad*2'  # c4, c5, c6 in 7 commits (bisect-test.sh's)

echo "| history | build | --ways | rounds | builds | cancelled | building | wall |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
for s in "${sleeps[@]}"; do
  for h in one two several; do
    last=$(( $(git -C "$t/$h" rev-list --count HEAD) - 1 ))
    for k in 1 3; do
      out="$t/$h-$s-$k"
      export RENDERAUDIT_BUILD_CACHE="$out.cache"
      t0=$(date +%s.%N)
      RA_TEST_SLEEP=$s "$ra" bisect "$t/run" --between faulty@good faulty@bad --source "$t/$h" \
        --good "$(c "$t/$h" 0)" --bad "$(c "$t/$h" "$last")" --build-command "$cmd" --out "$out" \
        --jobs 2 --max-primitives 6 --no-pictures --ways "$k" >"$out.out" 2>"$out.err" ||
        { cat "$out.err"; fail "$h --ways $k"; }
      wall=$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.0f s", b - a }')
      /usr/bin/python3 - "$out/bisect.json" "$h" "$s" "$k" "$wall" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
r = j["rounds"]
cancelled = sum(len(x["cancelled"]) for x in r)
building = sum(x["build_wall_s"] for x in r)
print("| %s | %s s | %s | %d | %d | %d | %.0f s | %s |" % (sys.argv[2], sys.argv[3], sys.argv[4],
      len(r), len(j["steps"]), cancelled, building, sys.argv[5]))
PY
    done
  done
done
