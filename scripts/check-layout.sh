#!/usr/bin/env bash
# Fails when a folder includes a folder that comes after it in the layout order (docs/development.md, "Source
# layout"). Tests (*_test.cpp, *_testing.h, tests/) and benchmarks may include anything.
set -euo pipefail
cd "$(dirname "$0")/.."
order=(util geometry platforms metrics runner stats analysis plots scenes timing terrain_lod regulation
       report audit app)
declare -A rank
for i in "${!order[@]}"; do rank[${order[$i]}]=$i; done
bad=0
for dir in "${order[@]}"; do
  while IFS=: read -r file _ inc; do
    target=${inc#*\"}; target=${target%%/*}
    [ -n "${rank[$target]+x}" ] || continue
    if [ "${rank[$target]}" -gt "${rank[$dir]}" ]; then
      echo "layout: $file includes $target/ (a folder after $dir/ in the layout order)"; bad=1
    fi
  done < <(grep -Hn '#include "[a-z_]*/' "$dir"/*.cpp "$dir"/*.h 2>/dev/null |
           grep -v '_test\.cpp:\|_testing\.h:\|_test_util\.h:\|_test\.h:' || true)
done
[ $bad -eq 0 ] && echo "layout: no folder includes one after it (${#order[@]} folders)"
exit $bad
