#include "platforms/platform.h"

#include "util/errors.h"

namespace ra {

const std::vector<PlatformSpec>& platform_specs() {
  static const std::vector<PlatformSpec> specs = {
      {"osmesa-llvmpipe", "Mesa OSMesa with the llvmpipe driver (the embedded default)", "llvmpipe"},
      {"osmesa-softpipe", "Mesa OSMesa with the softpipe driver (an independent second platform)",
       "softpipe"},
      {"reference", "the project's exact rasterizer following the GL rules (no driver)", nullptr},
      {"faulty", "test platform: the reference rasterizer plus the faults of [faults]", nullptr},
      // The antialiasing condition; last, so that the names before it keep their place in
      // messages. softpipe has no multisample variant: its GL_MAX_SAMPLES is 1 (Mesa 22.3.6), and
      // glRenderbufferStorageMultisample(4) fails there.
      {"osmesa-llvmpipe-msaa4",
       "Mesa OSMesa with llvmpipe, antialiased: 4x multisampling, coverage = samples lit / 4",
       "llvmpipe", 4},
  };
  return specs;
}

const PlatformSpec* find_platform(const std::string& name) {
  for (const auto& s : platform_specs())
    if (name == s.name) return &s;
  return nullptr;
}

std::string platform_names() {
  std::string out;
  for (const auto& s : platform_specs()) out += (out.empty() ? "" : ", ") + std::string(s.name);
  return out;
}

std::unique_ptr<Platform> create_platform(const std::string& name, const FaultPlan& faults) {
  const PlatformSpec* spec = find_platform(name);
  if (!spec) throw UserError("unknown platform '" + name + "' (allowed: " + platform_names() + ")");
  if (spec->gallium_driver) return create_osmesa_platform(*spec);
  if (name == "reference") return create_reference_platform();
  return create_faulty_platform(faults);
}

}  // namespace ra
