// The back ends behind create_gl_context (gl_context.cpp), one file each.
#pragma once

#include <memory>

#include "platforms/gl_context.h"

namespace ra::platforms {

std::unique_ptr<GlContext> create_osmesa_context(const rundir::PlatformSpec& spec);   // osmesa_context.cpp
std::unique_ptr<GlContext> create_egl_context(const rundir::PlatformSpec& spec);      // egl_context.cpp

}  // namespace ra::platforms
