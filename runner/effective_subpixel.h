// The subpixel grid a platform effectively snaps vertices to, measured by drawing: the grid (0 to
// 12 bits, rounding to nearest or truncating; 0 = no snapping, the exact reference) under which
// the reference rasterizer lights the same pixels as the platform for the most calibration
// triangles. It can differ from the GL_SUBPIXEL_BITS the driver reports: that value is only the
// driver's statement (GL requires at least 4), this one is what its pixels show.
//
// Calibration scene (window coordinates, px): kCalibrationTriangles triangles with vertices
// uniform in [8, 120]^2 of a 128 x 128 window at depth 1 in front of a 90-degree camera, so that
// the world coordinates the driver gets are exact in float and the window coordinates lie on a
// 2^-14 px grid (finer than every candidate grid: each candidate is a real snap).
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "geometry/reference_rasterizer.h"
#include "platforms/platform.h"

namespace ra::runner {

constexpr int kCalibrationTriangles = 96;
constexpr int kMaxCandidateSubpixelBits = 12;

struct SubpixelCandidate {
  geometry::SubpixelGrid grid;
  int matches = 0;  // calibration triangles whose pixels equal the reference on this grid
};

struct EffectiveSubpixel {
  geometry::SubpixelGrid
      grid;           // the best candidate (ties: exact first, then the finer grid, nearest first)
  int matches = 0;    // its matches, of `triangles`
  int triangles = 0;
  std::vector<SubpixelCandidate> candidates;  // every grid tried, in the order of the tie rule
};

// The calibration triangles (world coordinates of calibration_view()).
std::vector<geometry::Primitive> calibration_triangles();
geometry::View calibration_view();

// Draws the calibration triangles on `platform` (its current view is replaced by
// calibration_view(): set the view again afterwards) and scores every candidate grid.
EffectiveSubpixel measure_effective_subpixel(platforms::Platform& platform);

// {"bits", "rounding", "text", "matches", "triangles", "candidates": [{"grid", "matches"}, ...]}:
// what the run's driver file (drivers/P.json) says under "effective_subpixel".
nlohmann::json effective_subpixel_json(const EffectiveSubpixel& e);

}  // namespace ra::runner
