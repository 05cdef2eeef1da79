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
}

}  // namespace ra::platforms
