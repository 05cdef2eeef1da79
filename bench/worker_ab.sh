#!/usr/bin/env bash
# Two builds side by side on the same shards: `bench/worker_ab.sh OLD_BUILD NEW_BUILD [ROUNDS]
# [EXPERIMENT] -- SHARD...` runs each shard (PLATFORM:KIND:VIEW:COUNT, primitives 0..COUNT) with
# OLD_BUILD/renderaudit-worker and NEW_BUILD/renderaudit-worker alternately, ROUNDS times each
# (default 5; the first binary of a round alternates too), and prints per shard the median wall
# seconds of each, their ratio, and whether the two wrote the same records in every column but
# the timing ones (render_us, batch_size). Exit status 1 when any shard's records differ.
# What a performance change is judged by in docs/benchmarks.md: medians side by side on one machine,
# records identical. Example:
#   bench/worker_ab.sh /tmp/old/build build 5 -- osmesa-llvmpipe:triangle:7:3000 osmesa-llvmpipe:line:7:10000
set -euo pipefail

usage() {
  echo "usage: $0 OLD_BUILD NEW_BUILD [ROUNDS] [EXPERIMENT] -- PLATFORM:KIND:VIEW:COUNT..." >&2
  exit 2
}
[ $# -ge 4 ] || usage
old=$1 new=$2
shift 2
rounds=5 experiment=experiments/nist2008.toml
[ "$1" != -- ] && { rounds=$1; shift; }
[ "$1" != -- ] && { experiment=$1; shift; }
[ "$1" = -- ] || usage
shift
for b in "$old" "$new"; do
  [ -x "$b/renderaudit-worker" ] || { echo "$0: no $b/renderaudit-worker" >&2; exit 2; }
done
[ -f "$experiment" ] || { echo "$0: no experiment file $experiment" >&2; exit 2; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for side in old new; do
  mkdir -p "$work/$side/drivers" "$work/$side/records" "$work/$side/logs"
  cp "$experiment" "$work/$side/experiment.toml"
done

# The records without their timing columns, found by name in the header.
strip_timing() {
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "render_us" || $i == "batch_size") skip[i] = 1 }
           /^#/ { next }
           { line = ""; for (i = 1; i <= NF; ++i) if (!skip[i]) line = line $i ","; print line }' "$1"
}
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'; }

status=0
printf '| shard | old s (median of %d) | new s | new / old | records |\n| --- | ---: | ---: | ---: | --- |\n' "$rounds"
for spec in "$@"; do
  IFS=: read -r platform kind view count <<<"$spec"
  [ -n "$count" ] || usage
  : >"$work/old.times"
  : >"$work/new.times"
  for ((r = 0; r < rounds; ++r)); do
    order="old new"
    ((r % 2)) && order="new old"
    for side in $order; do
      bin=$old
      [ $side = new ] && bin=$new
      rm -f "$work/$side/records/"*
      t0=$(date +%s.%N)
      "$bin/renderaudit-worker" worker "$work/$side" "$platform" "$kind" "$view" 0 "$count" \
        >"$work/$side/logs/last.log" 2>&1 || { cat "$work/$side/logs/last.log" >&2; exit 2; }
      t1=$(date +%s.%N)
      echo "$t1 - $t0" | bc -l >>"$work/$side.times"
    done
  done
  file="$platform.$kind.v$view.0-$count.csv"
  same=identical
  if ! cmp -s <(strip_timing "$work/old/records/$file") <(strip_timing "$work/new/records/$file"); then
    same=DIFFERENT
    status=1
  fi
  mo=$(median <"$work/old.times") mn=$(median <"$work/new.times")
  printf '| %s | %.3f | %.3f | %.3f | %s |\n' "$spec" "$mo" "$mn" "$(echo "$mn / $mo" | bc -l)" "$same"
done
exit $status
