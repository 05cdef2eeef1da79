#!/usr/bin/env bash
# `make driver-upgrade PER_VIEW=N`: a copy of an experiment file at N primitives of each kind per
# view (each count its [primitives] table gives: points, lines, triangles), named NAME-N, its shards
# no larger than N, written to OUT.toml. The experiment in the repository stays as it is.
# Usage: cut-experiment.sh EXPERIMENT N OUT.toml
#        cut-experiment.sh --check N      (the check of N alone, before anything is built)
# Exit 2, saying why, when N is not a whole number from 1 to 100,000,000 (the most per kind and
# view an experiment may ask for) or EXPERIMENT cannot be read.
set -euo pipefail

check() {
  if ! [[ "$1" =~ ^[1-9][0-9]{0,8}$ ]] || [ "$1" -gt 100000000 ]; then
    echo "make driver-upgrade: PER_VIEW=$1 is not a number of primitives per kind and view:" \
         "give a whole number from 1 to 100000000, e.g. PER_VIEW=1000" >&2
    exit 2
  fi
}

if [ "${1:-}" = --check ]; then
  check "${2:-}"
  exit 0
fi
[ $# = 3 ] || { echo "usage: $0 EXPERIMENT N OUT.toml | --check N" >&2; exit 2; }
experiment=$1 n=$2 out=$3
check "$n"
[ -r "$experiment" ] || { echo "make driver-upgrade: cannot read $experiment" >&2; exit 2; }
mkdir -p "$(dirname "$out")"
shard=$(sed -n 's/^shard_size = \([0-9]*\).*/\1/p' "$experiment")
[ -n "$shard" ] && [ "$shard" -gt "$n" ] && shard=$n
sed -e "s/^name = \"\\([^\"]*\\)\"/name = \"\\1-$n\"/" \
    -e "s/^\\(points\\|lines\\|triangles\\) = [0-9]*/\\1 = $n/" \
    -e "${shard:+s/^shard_size = [0-9]*/shard_size = $shard/}" "$experiment" > "$out.tmp"
mv "$out.tmp" "$out"
echo "make driver-upgrade: $out: $experiment at $n primitives of each kind per view"
