// One case of the audit: render one primitive in one view on one platform and measure it against
// its ideal projection (NIST paper, section 3). Produces the case's record.
#pragma once

#include <string>

#include "runner/platform.h"
#include "runner/records.h"

namespace ra {

// Fills every column of the record but `platform` timing-independent fields come first; the
// reference rasterizer's pixel set is compared with the rendered one (ref_diff) unless the
// platform is itself exact (`compare_with_reference` false, ref_diff = 0).
Record measure_case(const std::string& platform_name, Platform& platform, const View& view,
                    const Primitive& prim, bool compare_with_reference);

// The record fields that describe the case itself (platform, view, kind, index).
Record case_identity(const std::string& platform_name, const View& view, const Primitive& prim);

}  // namespace ra
