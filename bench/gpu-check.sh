#!/usr/bin/env bash
# The GPU measurements of layered batches and of the lit-pixel scan on the device, in one run on a
# GPU node (docs/benchmarks.md, "Layered batches"). `make gpu-kit` prepares, on the build machine,
# dist/ with the lean bundle and the lean build's layered_bench; carry dist/ to the node and run
#   bench/gpu-check.sh dist OUT [PRIMITIVES]
# from the project's folder there. It prints, and writes to OUT/:
#   gpu.txt             the GPU and its driver; the node's platforms
#   layers-P.txt        layered_bench --versus layers on P (one layer against layered, identity)
#   scan-P.txt          layered_bench --versus scan on P (host scan against the device's)
#   quick-P/            the quick experiment on P (`run --jobs 8`; its time from start to sealed
#                       records is the step's), and its speed table
# for P = vk-device and egl-device, each step under its own time limit, so that a slow step costs
# its limit and no more. PRIMITIVES per kind and view for layered_bench (default 2000: 48,000 per
# way over the eight nist2008 views). PLATFORMS="..." measures other platforms (a dry run on the
# build machine: PLATFORMS="vk-lavapipe osmesa-llvmpipe").
set -uo pipefail
if [ $# -lt 2 ]; then
  echo "usage: $0 KIT_DIR OUT_DIR [PRIMITIVES]" >&2
  exit 2
fi
kit=$1 out=$2 primitives=${3:-2000}
platforms=${PLATFORMS:-vk-device egl-device}
for p in $platforms; do  # names go into file names and a sed replacement: platform names only
  if ! [[ $p =~ ^[A-Za-z0-9][A-Za-z0-9:@._-]*$ ]]; then
    echo "gpu-check: PLATFORMS: '$p' is not a platform name (letters, digits, : @ . _ -)" >&2
    exit 2
  fi
done
bundle=$(ls "$kit"/renderaudit-lean-*.tar.gz 2>/dev/null | head -1)
if [ -z "$bundle" ] || [ ! -x "$kit/layered_bench" ]; then
  echo "gpu-check: $kit holds no lean bundle and layered_bench: run 'make gpu-kit' first" >&2
  exit 2
fi
mkdir -p "$out"
out=$(cd "$out" && pwd)
unpacked=$(mktemp -d)
trap 'rm -rf "$unpacked"' EXIT
tar -C "$unpacked" -xzf "$bundle"
root=$(ls -d "$unpacked"/renderaudit-lean-*)
ra="$root/bin/renderaudit"
# layered_bench needs what the bundled program needs: the launcher's library path, as it sets it.
libs="$root/lib"
"$root/libexec/renderaudit" --version > /dev/null 2>&1 || libs="$root/lib/compat:$libs"
# (ldconfig's list read whole first: `ldconfig | grep -q` under pipefail fails when grep stops early)
known=$(/sbin/ldconfig -p 2>/dev/null || true)
grep -q 'libvulkan.so.1 ' <<<"$known" || libs="$libs:$root/lib/loaders/vulkan"
grep -q 'libEGL.so.1 ' <<<"$known" || libs="$libs:$root/lib/loaders/egl"
bench=(env "LD_LIBRARY_PATH=$libs${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" "$kit/layered_bench"
       --experiment "$root/experiments/nist2008.toml" --primitives "$primitives")
step() {  # step LIMIT_S NAME LOG COMMAND...: runs it into LOG, prints its time and exit status
  local limit=$1 name=$2 log=$3
  shift 3
  local t0=$SECONDS
  timeout "$limit" "$@" > "$log" 2>&1
  local rc=$?
  echo "[$name: exit $rc after $((SECONDS - t0)) s, limit $limit s]"
}

{
  date -u
  nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv 2>&1 || true
  nproc
  "$ra" --version
  "$ra" platforms
} > "$out/gpu.txt" 2>&1
cat "$out/gpu.txt"
for p in $platforms; do
  for way in layers scan; do
    step 150 "$way $p" "$out/$way-$p.txt" "${bench[@]}" --platform "$p" --versus "$way"
    cat "$out/$way-$p.txt"
  done
done
for p in $platforms; do
  exp="$out/quick-$p.toml"
  sed -e "s/^name = .*/name = \"quick-$p\"/" -e "s/^platforms = .*/platforms = [\"$p\"]/" \
    "$root/experiments/quick.toml" > "$exp"
  step 120 "quick $p" "$out/quick-$p.log" "$ra" run "$exp" --jobs 8 --out "$out/quick-$p"
  "$ra" analyze "$out/quick-$p" > /dev/null 2>&1 && cat "$out/quick-$p/analysis/speed.md" 2>/dev/null
done
