// Conformance verdicts: whether one primitive's lit pixels are what the OpenGL spec allows an
// implementation to produce, not only whether they equal the exact reference rasterizer's.
// Coordinates: GL window coordinates in pixels (pixel (i, j) covers [i, i+1) x [j, j+1), centre
// (i + 0.5, j + 0.5), y up), as in geometry/reference_rasterizer.h.
//
// What GL leaves to the implementation (OpenGL 4.6 core; the same text is in 2.1):
// - Subpixel precision: window coordinates may be snapped to a grid of GL_SUBPIXEL_BITS bits, and
//   the least value an implementation may report is 4 (chapter 23, implementation-dependent
//   values). A vertex may therefore move by up to 2^-4 px in x and in y: kSnapAllowancePx.
// - Floating point: results are accurate to "about 1 part in 10^5" (section 2.3.4.1). A window
//   coordinate of magnitude m may also be off by 1e-5 m (m at least the window's size), where m
//   is taken before clipping to the window's sides (near_clipped_window_magnitude): a guard-band
//   rasterizer carries vertices far outside the window, and clips them in float.
// Per kind, what may differ from the exact reference (the "allowance" below is the sum of both):
// - Polygons (14.6.1): a pixel whose centre lies within the allowance of an edge of the clipped
//   polygon (moving every vertex by at most d moves every edge by at most d). Broken: "polygon-edge".
// - Lines (14.5.1), other algorithms than diamond-exit are allowed when (1) every fragment lies
//   within one unit in x and in y of a diamond-exit fragment ("line-deviation"), (2) the fragment
//   count differs from diamond-exit's by at most one ("line-count"), (3) an x-major segment has no
//   two fragments in one column, a y-major one none in one row ("line-column"). Rule 4 (shared
//   ends of connected segments) does not apply to a lone segment. Diamond-exit is taken on the
//   exact ends, on the ends snapped to the platform's effective grid and on the ends snapped to
//   GL's coarsest grid (4 bits, either rounding); the best one counts.
//   Rule 2 is not judged where a window side cut an end (it counts fragments the window then
//   discards); rule 3 takes either axis as the major one where the allowance could swap them.
// - Points (14.4), size 1: exactly one fragment, the pixel containing the (snapped) position: any
//   pixel within the allowance of the position, in x and in y ("point-pixel", more than one:
//   "point-count"); none at all only when the position lies within the allowance of the clip
//   volume's boundary ("point-missing").
#pragma once

#include <cstdint>
#include <string>

#include "geometry/clipping.h"
#include "geometry/pixel_set.h"
#include "geometry/reference_rasterizer.h"
#include "geometry/view.h"
#include "metrics/records.h"

namespace ra {

// The least subpixel grid GL allows, 4 bits: a truncating snap moves a coordinate by < 2^-4 px.
constexpr int kLeastSubpixelBits = 4;
constexpr double kSnapAllowancePx = 0.0625;
// GL's "about 1 part in 10^5" for the results of floating-point operations.
constexpr double kFloatRelativeError = 1e-5;

struct ConformanceVerdict {
  Conformance conformance = Conformance::kNotCompared;
  int64_t violating_pixels = -1;  // 0 unless kViolation
  std::string violated_rules;     // '+'-joined rule names (above); empty unless kViolation
};

// The verdict for a rendered point, segment or triangle. `exact` is the exact reference's pixels
// (rasterize_* with an exact grid), `lit` the platform's; `effective` the grid the platform
// effectively snaps to (metrics/effective_subpixel.h; exact when it does not snap); `magnitude`
// near_clipped_window_magnitude() of the primitive. `violating`,
// when given, receives the pixels that break a rule (lit or left dark; a count rule names none).
ConformanceVerdict judge_point(Vec4 clip, int width, int height, const PixelSet& lit,
                               const PixelSet& exact, SubpixelGrid effective,
                               PixelSet* violating = nullptr);
ConformanceVerdict judge_segment(const ClippedSegment& segment, double magnitude, int width,
                                 int height,
                                 const PixelSet& lit, const PixelSet& exact,
                                 SubpixelGrid effective, PixelSet* violating = nullptr);
ConformanceVerdict judge_polygon(const ClippedPolygon& polygon, double magnitude, int width,
                                 int height,
                                 const PixelSet& lit, const PixelSet& exact,
                                 SubpixelGrid effective, PixelSet* violating = nullptr);

// The same for primitive `prim` under `view`, clipping it and rasterizing its exact reference here
// (for one primitive at a time, as `renderaudit show` needs; the runner reuses its own).
ConformanceVerdict judge_primitive(const View& view, const Primitive& prim, const PixelSet& lit,
                                   SubpixelGrid effective, PixelSet* violating = nullptr);

// The largest |window coordinate| (px) of the primitive clipped to the near plane only (w > 0):
// the scale of the floating-point error GL allows in its window coordinates. 0 when nothing of
// it lies in front of the near plane.
double near_clipped_window_magnitude(const View& view, const Primitive& prim);

// The allowance (px) of a window coordinate of magnitude up to `magnitude` in a width x height
// window: kSnapAllowancePx plus the floating-point error.
double conformance_allowance(double magnitude, int width, int height);

}  // namespace ra
