// One case of the audit: render one primitive in one view on one platform and measure it against
// its ideal projection (NIST paper, section 3). Produces the case's record.
#pragma once

#include <string>
#include <vector>

#include "geometry/clipping.h"
#include "geometry/pixel_region.h"
#include "metrics/point_metrics.h"
#include "platforms/platform.h"
#include "metrics/records.h"
#include "geometry/reference_rasterizer.h"

namespace ra::runner {

// Pixels of margin around the ideal primitive's window bounding box in which a platform's pixels are
// looked for first (the occlusion-query proof, or a full scan, covers the rest of the window).
constexpr int kRegionMargin = 2;
// Triangles whose box (with the margin) is larger than this many pixels are read back in bands
// of kTriangleBandRows rows (geometry/pixel_region.h band_region), smaller ones as their box.
constexpr int64_t kTriangleBandMinArea = 128 * 128;
constexpr int kTriangleBandRows = 32;

// Primitives are drawn in batches of up to kMaxBatch (Platform::render_batch). Those whose
// expected regions are disjoint and at most this large (px^2) share a layer of the window (on a
// platform with one layer: one completeness proof); a larger one takes a layer of its own (on a
// platform with one layer it is drawn alone, where the proof's fixed cost no longer matters).
constexpr int64_t kBatchMaxRegionArea = 64 * 64;
constexpr size_t kMaxBatch = 64;

// What each rendered case is compared with.
struct CaseComparison {
  // The exact reference rasterizer's pixels: ref_diff and the conformance verdict. False on the
  // reference platform itself (ref_diff 0, conformance exact).
  bool with_reference = true;
  // The conformance verdict (metrics/conformance.h); false only in benchmarks, to show its cost.
  bool conformance = true;
  // The grid the platform effectively snaps to (runner/effective_subpixel.h): "snapped" means
  // equal to the reference on this grid. Exact: the platform does not snap.
  geometry::SubpixelGrid effective;
  // How the platform draws lines, hence which reference and rules judge them: GL's diamond-exit
  // (GL platforms, Vulkan's Bresenham mode and default lines without strictLines), or Vulkan's
  // strict rectangles (metrics/conformance.h judge_rectangle_segment).
  enum class LineRule { kDiamondExit, kRectangle };
  LineRule line_rule = LineRule::kDiamondExit;
  // Implicit from a bool (with_reference), as most callers only say whether to compare.
  CaseComparison(bool with_reference_ = true, geometry::SubpixelGrid effective_ = {})
      : with_reference(with_reference_), effective(effective_) {}
};

// The line rule of a platform that loaded driver `driver`: kRectangle for a Vulkan platform
// drawing default lines on a device with strictLines, else kDiamondExit.
CaseComparison::LineRule line_rule_for(const rundir::PlatformSpec& spec,
                                       const platforms::DriverInfo& driver);

// Renders each of `prims` on `platform` and fills their records, in order: visibility, the kind's
// metrics, pixel hash, render time, and the comparison with the reference (ref_diff and the
// conformance verdict; see CaseComparison). Primitives with NaN/inf coordinates, or no projection, are never drawn:
// status invalid. `cost_us` (for benchmarks), when given, receives each primitive's share of the
// wall time in microseconds: its own geometry and measurement, plus an equal share of its batch's
// drawing and proof. `max_batch` 1 draws every primitive alone (for timing comparisons: then
// render_us is the primitive's own time on every platform, whatever its neighbours' pixels).
std::vector<metrics::Record> measure_cases(const std::string& platform_name, platforms::Platform& platform,
                                  const geometry::View& view,
                                  const std::vector<geometry::Primitive>& prims,
                                  const CaseComparison& comparison,
                                  std::vector<double>* cost_us = nullptr,
                                  size_t max_batch = kMaxBatch);
// The same for one primitive.
metrics::Record measure_case(const std::string& platform_name, platforms::Platform& platform,
                    const geometry::View& view, const geometry::Primitive& prim,
                    const CaseComparison& comparison);

// Visibility of a segment or triangle (no multiple-visible class for them, paper 3.5-3.6).
metrics::Visibility classify_extended(bool ideal_visible, size_t lit_pixels);

// Fill pixels, visibility and, for true-visible cases, the metrics (paper 3.5 and 3.6).
void measure_segment_case(const geometry::ClippedSegment& seg, const geometry::View& view,
                          const geometry::PixelSet& lit, metrics::Record& rec);
void measure_triangle_case(const geometry::ClippedPolygon& poly, const geometry::View& view,
                           const geometry::PixelSet& lit, metrics::Record& rec);
// The same for an antialiased rendering (RenderResult::samples > 0): the te_* columns get the
// coverage form of the metrics (TEs_cov, TEu_cov, triangle_metrics.h); visibility and `pixels`
// count the pixels with any coverage.
void measure_triangle_coverage_case(const geometry::ClippedPolygon& poly,
                                    const geometry::View& view,
                                    const platforms::RenderResult& rendered, metrics::Record& rec);

// The record's pixel_hash: pixel_set_hash(lit) for an aliased rendering; for an antialiased one
// the same FNV-1a 64 continued over the samples-lit byte of each lit pixel in (y, x) order, so a
// change of coverage alone changes the hash.
uint64_t rendered_pixel_hash(const platforms::RenderResult& rendered);

// The record fields that describe the case itself (platform, view, kind, index).
metrics::Record case_identity(const std::string& platform_name, const geometry::View& view,
                     const geometry::Primitive& prim);

}  // namespace ra::runner
