// Filling the GL function table (see the header).
#include "platforms/gl_api.h"

#include <stdexcept>
#include <string>

namespace ra::platforms {

void GlApi::load(const std::function<void*(const char*)>& get_proc) {
#define RA_GL_LOAD(name)                                                                 \
  name = reinterpret_cast<decltype(name)>(get_proc("gl" #name));                        \
  if (!name) throw std::runtime_error("the GL driver does not provide gl" #name);
  RA_GL_FUNCTIONS(RA_GL_LOAD)
#undef RA_GL_LOAD
#define RA_GL_LOAD_OPTIONAL(name) name = reinterpret_cast<decltype(name)>(get_proc("gl" #name));
  RA_GL_COMPUTE_FUNCTIONS(RA_GL_LOAD_OPTIONAL)
#undef RA_GL_LOAD_OPTIONAL
}

bool GlApi::has_compute() const {
  bool all = true;
#define RA_GL_GIVEN(name) all = all && name != nullptr;
  RA_GL_COMPUTE_FUNCTIONS(RA_GL_GIVEN)
#undef RA_GL_GIVEN
  return all;
}

}  // namespace ra::platforms
