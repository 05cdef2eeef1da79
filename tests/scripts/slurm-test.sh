#!/usr/bin/env bash
# `make slurm-test`: `renderaudit run --slurm` on a real Slurm (one machine, scripts/slurm-local.sh).
#
#   1. experiments/quick.toml as a job array of 4 slices: the gathered run's records equal a local
#      run's in every column but render_us and host_us, and `audit` against the local run says unchanged.
#   2. tests/data/slurm_faults.toml (both Mesa platforms, 128 shards of unequal cost) with one task
#      cancelled by scancel in the middle of its slice and another requeued (what Slurm does when
#      a node fails) in the middle of its own: the gathered run is complete, every primitive is
#      there once, and its records equal a local run's.
#
# Usage: tests/scripts/slurm-test.sh [BUILD_DIR]   (default build). Exit 0 pass, 1 fail, 77 when no
# Slurm cluster could be started here (not root, no packages): the test is then skipped, loudly.
set -uo pipefail

build=${1:-build}
ra=$(cd "$build" && pwd)/renderaudit
repo=$(cd "$(dirname "$0")/../.." && pwd)
work=$(cd "$build" && pwd)/slurm-test   # under the build tree
# One node: a run directory under /tmp (a checkout there) is as shared as any, so allow it.
one_node=--allow-node-local
state=${RENDERAUDIT_SLURM_STATE:-/tmp/renderaudit-slurm-test}
export SLURM_CONF=$state/slurm.conf
export PATH=$PATH:/usr/sbin

fail() { echo "slurm-test: FAIL: $*" >&2; exit 1; }
step() { echo "slurm-test: $*"; }

[ -x "$ra" ] || fail "$ra not built"
if ! "$repo/scripts/slurm-local.sh" start "$state"; then
  echo "slurm-test: SKIPPED: no Slurm cluster could be started on this machine" >&2
  exit 77
fi
trap '"$repo/scripts/slurm-local.sh" stop "$state" >/dev/null 2>&1' EXIT
rm -rf "$work"
mkdir -p "$work"

# The records of a run (either file format, `renderaudit records`) with their timing columns
# (render_us and host_us, the 33rd and 38th) left out, sorted.
records_without_timing() {
  "$ra" records "$1" | tail -n +2 | cut -d, -f1-32,34-37,39- | sort
}
same_records() {  # LOCAL SLURM
  records_without_timing "$1" >"$work/a.csv"
  records_without_timing "$2" >"$work/b.csv"
  [ -s "$work/a.csv" ] || fail "$1 holds no records"
  cmp -s "$work/a.csv" "$work/b.csv" ||
    fail "$2 differs from $1 in non-timing columns: $(diff "$work/a.csv" "$work/b.csv" | grep -c '^[<>]') lines"
  step "  records identical in every non-timing column ($(wc -l <"$work/a.csv") rows)"
}
wait_for() {  # SECONDS DESCRIPTION COMMAND...: polls every 0.2 s
  local limit=$1 what=$2
  shift 2
  for _ in $(seq $((limit * 5))); do "$@" && return 0; sleep 0.2; done
  fail "waited ${limit} s for $what"
}
task_state() { squeue -h -r -j "$1" -o '%T' 2>/dev/null; }
slice_running_with_shards_done() {  # ARRAY_JOB K: the task runs and has finished a shard or more
  [ "$(task_state "$1_$2")" = RUNNING ] || return 1
  local p="$dir/slices/$2/progress.json"
  [ -f "$p" ] && grep -q '"shards_finished": [1-9]' "$p" && grep -q '"finished": false' "$p"
}

# 1. quick.toml, 4 slices, two at a time
step "1. experiments/quick.toml: local run, then a Slurm job array of 4 slices"
"$ra" run "$repo/experiments/quick.toml" --out "$work/quick-local" --quiet >/dev/null ||
  fail "local run of quick.toml"
dir=$work/quick-slurm
t0=$(date +%s.%N)
"$ra" run "$repo/experiments/quick.toml" --out "$dir" --slurm --slices 4 --jobs 1 \
  --max-parallel 2 $one_node || fail "submission"
"$ra" status "$dir" --wait --every 0.5 || fail "status after the gather: $("$ra" status "$dir")"
step "  submitted to complete in $(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }') s"
[ "$(cat "$dir/slurm/gather.exit")" = 0 ] || fail "gather exit $(cat "$dir/slurm/gather.exit")"
same_records "$work/quick-local" "$dir"
"$ra" audit "$work/quick-local" "$dir" --no-history --max-rerenders 0 --out "$work/quick-audit" \
  >"$work/quick-audit.log" || fail "audit against the local run is not clean: $work/quick-audit.log"
step "  audit against the local run: unchanged"

# 2. faults: one task cancelled, one requeued, both in the middle of their slices
step "2. tests/data/slurm_faults.toml: scancel one task, requeue another, mid-slice"
"$ra" run "$repo/tests/data/slurm_faults.toml" --out "$work/faults-local" --quiet >/dev/null ||
  fail "local run of slurm_faults.toml"
dir=$work/faults-slurm
"$ra" run "$repo/tests/data/slurm_faults.toml" --out "$dir" --slurm --slices 4 --jobs 1 \
  --max-parallel 2 $one_node >"$work/submit.log" || fail "submission: $(cat "$work/submit.log")"
array=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["array_job"])' \
  "$dir/slurm/jobs.json")
wait_for 120 "task ${array}_1 to finish a shard" slice_running_with_shards_done "$array" 1
scancel "${array}_1"
step "  scancel ${array}_1 after $(grep -o '"shards_finished": [0-9]*' "$dir/slices/1/progress.json")"
wait_for 120 "task ${array}_2 to finish a shard" slice_running_with_shards_done "$array" 2
scontrol requeue "${array}_2" || fail "scontrol requeue ${array}_2"
# Slurm holds a requeued task back for two minutes (its begin time); a test need not wait
wait_for 30 "task ${array}_2 to be requeued" bash -c "grep -qx PENDING <<<\"\$(squeue -h -r -j ${array}_2 -o %T)\""
scontrol update JobId="${array}_2" StartTime=now || fail "scontrol update ${array}_2 StartTime=now"
step "  requeue ${array}_2 after $(grep -o '"shards_finished": [0-9]*' "$dir/slices/2/progress.json")"
"$ra" status "$dir" --wait --every 0.5 >"$work/faults-status.log" ||
  fail "the run did not complete: $(cat "$work/faults-status.log")"
cat "$work/faults-status.log"
[ "$(cat "$dir/slurm/gather.exit")" = 0 ] || fail "gather exit $(cat "$dir/slurm/gather.exit")"
python3 - "$dir" <<'EOF' || fail "the manifests do not show the faults as expected"
import json, sys
d = sys.argv[1]
s1 = json.load(open(d + "/slices/1/manifest.json"))
s2 = json.load(open(d + "/slices/2/manifest.json"))
m = json.load(open(d + "/manifest.json"))
assert s1["status"] == "interrupted", ("slice 1 was cancelled", s1["status"])
assert len(s2["invocations"]) == 2, ("slice 2 ran twice (requeued)", len(s2["invocations"]))
assert s2["status"] == "complete", ("slice 2 resumed to the end", s2["status"])
gather = m["invocations"][-1]
assert gather["shards_to_run"] > 0, "the gather ran the cancelled slice's missing shards"
assert m["status"] == "complete" and m["shards"]["complete"] == m["shards"]["total"] == 128
print("slurm-test:   slice 1 interrupted, slice 2 resumed after requeue, the gather ran %d "
      "shards the cancelled slice left" % gather["shards_to_run"])
EOF
rows=$(records_without_timing "$dir" | wc -l)
keys=$(records_without_timing "$dir" | cut -d, -f1,2,10,11 | sort -u | wc -l)
[ "$rows" = 32000 ] && [ "$keys" = 32000 ] ||
  fail "$rows rows and $keys distinct primitives where 32000 were planned"
step "  32000 primitives, each once"
same_records "$work/faults-local" "$dir"
step "PASS"
