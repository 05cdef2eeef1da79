#!/usr/bin/env bash
# The GPU measurement script (bench/gpu-check.sh; ctest gpu_check), run here on Mesa's drivers as
# docs/operations.md says to try it before a GPU is at hand: from a kit like `make gpu-kit`'s
# (the bundle, layered_bench and the validation layer), every step exits 0, both benchmarks
# compare identical records and print where the time went, the quick experiment runs to 64,000
# records and a speed table, and Khronos validation loads and reports nothing on lavapipe.
# Usage: gpu-check-test.sh BUILD_DIR
source "$(dirname "$0")/test-common.sh"  # build, root, t, fail, require_built
require_built renderaudit-lean renderaudit-worker layered_bench
"$root/scripts/make-bundle.sh" "$build/renderaudit-lean" "$build/renderaudit-worker" "$t/kit" > /dev/null ||
  { echo "FAIL: make-bundle.sh"; exit 1; }
install -m 755 "$build/layered_bench" "$t/kit/layered_bench"
"$root/scripts/kit-validation-layer.sh" "$t/kit" 2> /dev/null || fail "kit-validation-layer.sh"

platforms="osmesa-llvmpipe vk-lavapipe"
vulkan_why=$("$build/renderaudit-lean" platforms 2>&1 | grep '^vk-lavapipe ' | grep 'cannot draw')
[ -n "$vulkan_why" ] && platforms="osmesa-llvmpipe"  # no lavapipe here: GL alone
(cd "$root" && PLATFORMS="$platforms" bench/gpu-check.sh "$t/kit" "$t/out" 20) > "$t/log" 2>&1 ||
  fail "gpu-check.sh: exit $?"
grep -q "^renderaudit " "$t/out/gpu.txt" || fail "gpu.txt names no program version"
steps=$(grep -c '^\[.*: exit ' "$t/log")
failed=$(grep '^\[.*: exit ' "$t/log" | grep -vc ': exit 0 ')
# 3 steps per platform, and 2 validation steps per Vulkan platform when the kit has the layer
validated=""
[ -d "$t/kit/vulkan-validation" ] && validated=$(grep -o 'vk-[^ ]*' <<<"$platforms")
expected=$((3 * $(wc -w <<<"$platforms") + 2 * $(wc -w <<<"$validated")))
[ "$steps" = "$expected" ] || fail "$steps steps ran, not $expected"
[ "$failed" = 0 ] || fail "$failed steps failed: $(grep '^\[.*: exit ' "$t/log" | grep -v ': exit 0 ')"
for p in $platforms; do
  for way in layers scan; do
    f="$t/out/$way-$p.txt"
    grep -q "NOT IDENTICAL" "$f" && fail "$way-$p: records differ"
    # six rows (3 kinds x 2 windows) of records compared, each all identical (80 = 20 x 4 views)
    n=$(awk '$3 == 80 && $4 == 80' "$f" | wc -l)
    [ "$n" = 6 ] || fail "$way-$p: $n rows of 80 identical records, not 6"
    grep -q "Where the time went" "$f" || fail "$way-$p: no table of where the time went"
  done
  rows=$(for f in "$t/out/quick-$p"/records/*.csv.zst; do zstdcat "$f" | grep -vc '^#'; done |
    awk '{s += $1 - 1} END {print s}')
  [ "$rows" = 64000 ] || fail "quick-$p: $rows records, not 64000"
  [ -s "$t/out/quick-$p/analysis/speed.md" ] || fail "quick-$p: no speed table"
done
for p in $validated; do
  for way in layers scan; do
    f="$t/out/validation-$way-$p.log"
    [ -f "$f" ] || fail "validation-$way-$p: the layer did not load (no $f)"
    [ -f "$f" ] && grep -q 'Validation Error' "$f" && fail "validation-$way-$p: $(grep -c 'Validation Error' "$f") errors"
  done
done

if [ $bad -ne 0 ]; then
  sed -n 1,40p "$t/log"
  exit 1
fi
echo "gpu-check.sh on $platforms: every step exit 0, records identical both ways, quick runs complete"
