#include "platforms/platform.h"

#include "util/errors.h"

namespace ra::platforms {

std::unique_ptr<Platform> create_platform(const rundir::PlatformSpec& spec, const rundir::FaultPlan& faults) {
  if (spec.draws_with_gl()) return create_gl_platform(spec);
  if (spec.draws_with_vulkan()) return create_vulkan_platform(spec);
  if (spec.backend == rundir::Backend::kReference) return create_reference_platform();
  return create_faulty_platform(faults);
}

}  // namespace ra::platforms
