#!/usr/bin/env bash
# The drawing paths under the GL and Vulkan APIs' own validators (ctest api_validation): Mesa's
# reports of GL errors (MESA_DEBUG) on llvmpipe and zink, and Khronos validation with synchronization
# validation on lavapipe, which runs commands in order and so hides a missing barrier that a GPU
# would not. Each validator is first shown to catch a deliberate misuse
# (tests/api_misuse_probe.cpp); then the tests of every drawing path (one primitive at a time,
# layered batches, the scan on the device, multisampling, Bresenham lines) and the layered benchmark
# both ways run under it, and it must report nothing.
# Exit 1 naming the package when the validation layer is missing; 77 (skipped) when lavapipe
# cannot be brought up here and the GL half passed.
# Usage: api-validation-test.sh BUILD_DIR
source "$(dirname "$0")/test-common.sh"  # build, root, t, fail, require_built
require_built renderaudit_tests layered_bench api_misuse_probe
bench=("$build/layered_bench" --experiment "$root/experiments/nist2008.toml" --primitives 40)

# Runs "$@" with its output in $t/$name.log; fails when it exits non-zero or when a line
# matches $pattern (the validator's report), printing how many and the first three.
check_clean() {
  local name=$1 pattern=$2
  shift 2
  "$@" > "$t/$name.log" 2>&1 || fail "$name: exit $? ($(tail -n 3 "$t/$name.log" | tr '\n' ' '))"
  local n
  n=$(grep -cE "$pattern" "$t/$name.log")
  [ "$n" = 0 ] || fail "$name: the validator reported $n times; the first:"$'\n'"$(grep -E "$pattern" \
    "$t/$name.log" | awk 'NR <= 3' | cut -c1-400)"
}

# The paths' tests: the Mesa drivers' layered batches and device scan (MesaDrivers/*), the GL
# framebuffer, readback and multisampling, the Vulkan device's own tests.
gl_tests='MesaDrivers/*:ColourDepthFramebufferTest.*:ReadbackMeasurement.*:OsmesaMsaa.*:CaseMeasurement*:LayeredBatchesProof.*:TriangleCoverage.*'
# (zink's tests are left out of Vulkan validation: its Vulkan calls are Mesa's, and Mesa 22.3's
# zink makes some that the validator refuses.)
vulkan_tests='MesaDrivers/*:VulkanLavapipe.*:VulkanDeviceChoice.*:VulkanRectangleLines.*-*/egl_zink'

# GL: Mesa prints "Mesa: User error: GL_... in glCall(...)" for every GL error under MESA_DEBUG.
gl_report='^Mesa: (User error|warning)'
MESA_DEBUG=1 "$build/api_misuse_probe" gl > "$t/gl-probe.log" 2>&1 ||
  fail "api_misuse_probe gl: exit $? ($(tr '\n' ' ' < "$t/gl-probe.log"))"
grep -qE "$gl_report" "$t/gl-probe.log" || fail "MESA_DEBUG reported no error for glEnable(0xdead):" \
  "GL errors would go unseen ($(tr '\n' ' ' < "$t/gl-probe.log"))"
export MESA_DEBUG=1
check_clean gl-tests "$gl_report" "$build/renderaudit_tests" --gtest_filter="$gl_tests"
check_clean gl-layers "$gl_report" "${bench[@]}" --platform osmesa-llvmpipe
check_clean gl-scan "$gl_report" "${bench[@]}" --platform osmesa-llvmpipe --versus scan
unset MESA_DEBUG

# Vulkan: errors only (the warnings are design choices: every image in VK_IMAGE_LAYOUT_GENERAL,
# vulkan_resources.h), synchronization validation on, each report a "Validation Error" line.
cat > "$t/vk_layer_settings.txt" <<'EOF'
khronos_validation.report_flags = error
khronos_validation.enables = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT
khronos_validation.debug_action = VK_DBG_LAYER_ACTION_LOG_MSG
khronos_validation.log_filename = stdout
EOF
export VK_INSTANCE_LAYERS=VK_LAYER_KHRONOS_validation VK_LAYER_SETTINGS_PATH=$t
vk_report='Validation Error'
"$build/api_misuse_probe" vulkan > "$t/vk-probe.log" 2>&1
probe=$?
if [ $probe = 1 ] && [ $bad = 0 ]; then
  echo "SKIP (Vulkan half): $(tr '\n' ' ' < "$t/vk-probe.log")"
  exit 77
fi
[ $probe = 0 ] || fail "api_misuse_probe vulkan: exit $probe ($(tr '\n' ' ' < "$t/vk-probe.log"))"
if ! grep -q "SYNC-HAZARD-READ-AFTER-WRITE" "$t/vk-probe.log"; then
  if ! ls /usr/share/vulkan/explicit_layer.d/*khronos_validation* > /dev/null 2>&1; then
    echo "FAIL: the Khronos validation layer is not installed: Debian package vulkan-validationlayers" \
      "(scripts/install-deps.sh installs it)"
    exit 1
  fi
  fail "synchronization validation missed a fill read by a copy with no barrier:" \
    "Vulkan hazards would go unseen ($(tr '\n' ' ' < "$t/vk-probe.log" | cut -c1-2000))"
fi
check_clean vk-tests "$vk_report" "$build/renderaudit_tests" --gtest_filter="$vulkan_tests"
check_clean vk-layers "$vk_report" "${bench[@]}" --platform vk-lavapipe
check_clean vk-scan "$vk_report" "${bench[@]}" --platform vk-lavapipe --versus scan
[ $bad = 0 ] && echo "OK: no GL error and no Vulkan validation error or hazard on any drawing path"
exit $bad
