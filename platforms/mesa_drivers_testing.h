// Test support (platforms/ and runner/ tests): the Mesa drivers that the device-level tests run on,
// each test skipped where its driver cannot be brought up, and the tests named by platform
// (".../egl_zink") so that a filter can pick drivers: tests/scripts/api-validation-test.sh leaves zink
// out of Vulkan validation, since zink's Vulkan calls are Mesa's, not the project's.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace ra::platforms::testing {

// llvmpipe through GL, lavapipe through Vulkan, and zink on lavapipe (GL whose commands become
// Vulkan submissions, as on a GPU's Vulkan driver).
inline auto mesa_drivers() {
  return ::testing::Values("osmesa-llvmpipe", "vk-lavapipe", "egl-zink");
}

// "egl-zink" -> "egl_zink" (test names take letters, digits and underscores).
inline std::string platform_test_name(const ::testing::TestParamInfo<const char*>& info) {
  std::string name = info.param;
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

}  // namespace ra::platforms::testing
