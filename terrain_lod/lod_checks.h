// Verification of a refined mesh, per frame (verified, not assumed):
//  (a) conformity: the triangles tile the terrain's rectangle exactly once, with no T-junction or
//      crack, checked on the whole mesh (all tiles together, so across seams too), and each tile
//      seam used by the same vertices from both sides;
//  (b) screen error: the largest on-screen distance between a full-resolution grid vertex
//      (x, y, z) and the LOD surface above it (x, y, z_lod(x, y)), both projected by the camera.
// Units: grid vertices (global numbers gj * nx + gi), metres, pixels (window coordinates, origin at
// the window's lower-left corner).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "scenes/scene.h"
#include "terrain_lod/lod_refinement.h"
#include "scenes/camera.h"

namespace ra::lod {

struct ConformityResult {
  bool conforming = false;
  size_t inverted = 0;          // triangles not counter-clockwise (or of zero area)
  size_t overlapping = 0;       // directed edges used twice (two triangles on one side)
  size_t open_edges = 0;        // edges with a triangle on one side only, not on the outer boundary
  size_t t_junctions = 0;       // edges with a used vertex strictly inside them
  bool area_matches = false;    // the triangles' areas sum to the rectangle's
  std::string first_problem;    // empty when conforming
};

// `triangles`: counter-clockwise, global vertex numbers of an nx x ny grid.
ConformityResult check_conformity(const std::vector<Triangle>& triangles, int nx, int ny);
std::vector<Triangle> all_triangles(const LodMesh& mesh);

struct SeamResult {
  bool ok = true;
  size_t seams = 0;             // tile edges shared by two tiles
  size_t mismatched = 0;        // seam vertices used by one side only
  std::string first_problem;
};

// For each edge shared by two tiles: the seam vertices used by the triangles of one tile equal
// those used by the other's.
SeamResult check_seams(const LodMesh& mesh, const TerrainHierarchy& h);

// z_lod at every grid vertex: the height of the LOD surface above it, metres (nx * ny).
std::vector<double> lod_surface_heights(const LodMesh& mesh, const HeightField& field);

struct ScreenErrorResult {
  double max_px = 0;           // largest distance, pixels (infinite when there is a hole)
  size_t checked = 0;          // grid vertices measured (segment wholly or partly in the frustum)
  size_t partially_visible = 0;  // of those, segments clipped by the frustum (visible part measured)
  size_t excluded = 0;         // left out: the segment lies wholly outside the view frustum
  size_t holes = 0;            // grid vertices that no LOD triangle covers (z_lod not finite)
  int worst_vertex = -1;       // global vertex of the maximum (the first hole, when there is one)
  double worst_x = 0, worst_y = 0;  // where it is on screen (visible end nearest the full-resolution
                                    // point), pixels; NaN for a hole behind the camera
};

// The screen error of the LOD surface `z_lod` (lod_surface_heights) against `field`. Each grid
// vertex's error segment, full-resolution point (x, y, z) to LOD point (x, y, z_lod), is clipped in
// homogeneous clip space against the six planes of the view frustum (near, far, the window's four
// edges; Liang-Barsky), and the pixel length of the part inside is measured: a segment crossing a
// window edge or corner (where the perspective stretch is largest) counts with its visible part, a
// segment crossing the near plane with the part in front of it. Only segments wholly outside the
// frustum are excluded (no pixel shows them). A vertex without LOD surface (a hole) is counted in
// `holes` and makes max_px infinite.
ScreenErrorResult measure_screen_error(const std::vector<double>& z_lod, const HeightField& field,
                                       const scenes::CameraSettings& cam,
                                       const scenes::Viewpoint& vp);

// Liang-Barsky clipping of the clip-space segment a + t (b - a), t in [0, 1], against
// -w <= x, y, z <= w: the visible part is [*t0, *t1]; false when no part is inside.
bool clip_segment(const geometry::Vec4& a, const geometry::Vec4& b, double* t0, double* t1);

}  // namespace ra::lod
