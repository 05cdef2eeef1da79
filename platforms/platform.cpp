#include "platforms/platform.h"

#include "util/errors.h"

namespace ra {

std::unique_ptr<Platform> create_platform(const std::string& name, const FaultPlan& faults) {
  const std::optional<PlatformSpec> spec = find_platform(name);
  if (!spec) throw UserError("unknown platform '" + name + "' (allowed: " + platform_names() + ")");
  if (spec->draws_with_gl()) return create_gl_platform(*spec);
  if (spec->backend == Backend::kReference) return create_reference_platform();
  return create_faulty_platform(faults);
}

}  // namespace ra
