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
#   validation-WAY-P.log  for a Vulkan P, when the kit carries the validation layer
#                       (scripts/kit-validation-layer.sh): every error and hazard Khronos validation
#                       with synchronization validation reports in layered_bench --versus WAY at 40
#                       primitives per kind and view (the file is created when the layer loads)
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
# Validation last: it measures nothing, and a slow GPU node spends its time on the measurements.
layer_dir=$kit/vulkan-validation
for p in $platforms; do
  [[ $p == vk-* && -f $layer_dir/VkLayer_khronos_validation.json ]] || continue
  for way in layers scan; do
    log="$out/validation-$way-$p.log"
    rm -f "$log"
    settings=$(mktemp -d -p "$unpacked")
    printf '%s\n' "khronos_validation.report_flags = error" \
      "khronos_validation.enables = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT" \
      "khronos_validation.debug_action = VK_DBG_LAYER_ACTION_LOG_MSG" \
      "khronos_validation.log_filename = $log" > "$settings/vk_layer_settings.txt"
    step 60 "validation $way $p" "$out/validation-$way-$p.txt" \
      env "VK_LAYER_PATH=$(cd "$layer_dir" && pwd)" VK_INSTANCE_LAYERS=VK_LAYER_KHRONOS_validation \
      "VK_LAYER_SETTINGS_PATH=$settings" \
      "${bench[@]}" --primitives 40 --platform "$p" --versus "$way"
    if [ -f "$log" ]; then
      echo "[validation $way $p: $(grep -c 'Validation Error' "$log") errors and hazards reported]"
    else
      echo "[validation $way $p: the validation layer did not load]"
    fi
  done
done
