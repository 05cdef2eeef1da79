// One case of the audit: render one primitive in one view on one platform and measure it against
// its ideal projection (NIST paper, section 3). Produces the case's record.
#pragma once

#include <string>

#include "runner/clipping.h"
#include "runner/platform.h"
#include "runner/records.h"

namespace ra {

// Pixels of margin around the ideal primitive's window bounding box in which a platform's pixels are
// looked for first (the occlusion-query proof, or a full scan, covers the rest of the window).
constexpr int kRegionMargin = 2;

// Renders `prim` on `platform` and fills its record: visibility, the kind's metrics, pixel hash,
// render time. The reference rasterizer's pixel set is compared with the rendered one (ref_diff)
// unless the platform is itself the reference (`compare_with_reference` false: ref_diff = 0).
Record measure_case(const std::string& platform_name, Platform& platform, const View& view,
                    const Primitive& prim, bool compare_with_reference);

// Visibility of a segment or triangle (no multiple-visible class for them, paper 3.5-3.6).
Visibility classify_extended(bool ideal_visible, size_t lit_pixels);

// Fill pixels, visibility and, for true-visible cases, the metrics (paper 3.5 and 3.6).
void measure_segment_case(const ClippedSegment& seg, const View& view, const PixelSet& lit,
                          Record& rec);
void measure_triangle_case(const ClippedPolygon& poly, const View& view, const PixelSet& lit,
                           Record& rec);

// The record fields that describe the case itself (platform, view, kind, index).
Record case_identity(const std::string& platform_name, const View& view, const Primitive& prim);

}  // namespace ra
