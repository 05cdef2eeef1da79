// The reference platform: what an exact rasterizer following the GL rules lights for a primitive,
// computed from the same double-precision projection the metrics use (no driver involved).
#pragma once

#include "runner/pixel_set.h"
#include "runner/primitive.h"
#include "runner/view.h"

namespace ra {

// Pixels the reference rasterizer lights for `prim` under `view` (GL window coordinates).
PixelSet reference_render(const View& view, const Primitive& prim);

}  // namespace ra
