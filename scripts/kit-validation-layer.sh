#!/usr/bin/env bash
# Copies the Khronos validation layer installed here (Debian's vulkan-validationlayers) into
# KIT/vulkan-validation/, its manifest naming the library beside it, so that bench/gpu-check.sh
# can validate the Vulkan paths on a GPU node that has no such package. Says so and exits 0 when
# the layer is not installed: the kit then measures without validating.
# Usage: kit-validation-layer.sh KIT_DIR
set -euo pipefail
kit=${1:?usage: $0 KIT_DIR}
manifest=/usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json
library=$(ls /usr/lib/*/libVkLayer_khronos_validation.so 2>/dev/null | awk 'NR == 1')
if [ ! -f "$manifest" ] || [ -z "$library" ]; then
  echo "kit-validation-layer: no Khronos validation layer here (apt-get install vulkan-validationlayers);" \
    "the kit will not validate the Vulkan paths" >&2
  exit 0
fi
mkdir -p "$kit/vulkan-validation"
install -m 644 "$library" "$kit/vulkan-validation/libVkLayer_khronos_validation.so"
# A library path with a slash is taken relative to the manifest's folder.
sed -E 's#("library_path": *")[^"]*"#\1./libVkLayer_khronos_validation.so"#' "$manifest" \
  > "$kit/vulkan-validation/VkLayer_khronos_validation.json"
grep -q '"library_path": *"./libVkLayer_khronos_validation.so"' "$kit/vulkan-validation/VkLayer_khronos_validation.json" ||
  { echo "kit-validation-layer: $manifest has no library_path to rewrite" >&2; exit 1; }
