// The experiment file of the terrain level-of-detail study: a top-level [lod] table.
// Every key is checked before anything renders; an unknown key, a wrong type or a value out of
// range is a UserError "FILE:LINE:COLUMN: 'lod.key' = V is out of range (allowed: ...)".
// Units: metres (x east, y north, z up), pixels, degrees.
//
//   name = "lod"                    # optional: default the file's stem
//   title = "..."                   # optional: the report's title
//   [lod]
//   platform = "osmesa-llvmpipe"    # or "osmesa-softpipe"
//   window = [1024, 768]            # pixels, 16..4096 each
//   fov_deg = 60                    # VERTICAL field of view, (0, 180)
//   near = 1                        # metres, > 0
//   far = 50000                     # metres, > near
//   tau = [0.5, 1, 2, 4, 8]         # screen-space error thresholds, pixels, each in (0, 1000]
//   lambda = "window"               # refinement's lambda: "window" (conservative, default),
//                                   #   "planar" w / (2 tan(phi/2)), "spherical" w / phi
//   check_lambdas = ["planar", "spherical"]  # also refined and checked (not drawn) per frame
//   error_propagation = "nested"    # or "unnested": the deliberately broken LOD (checks fail)
//   seams = "equalised"             # or "independent": tile edge errors not made equal (cracks)
//   tile_size = 257                 # vertices per tile side, 2^k + 1 in 3..4097
//   tiles = [2, 2]                  # tiles along x and y, 1..64 each (a height file is cropped
//                                   #   to at most this many); the terrain, (tiles (tile_size - 1)
//                                   #   + 1) per side, may have at most 2^24 vertices
//   spacing = 10                    # metres between grid vertices, (0, 100000]
//   height_scale = 300              # metres: the generated terrain's range / a file's multiplier
//   seed = 1                        # generated terrain, 0..2^63-1
//   feature_size = 800              # metres, wavelength of the coarsest octave, (0, 1e7]
//   octaves = 6                     # 1..16
//   persistence = 0.5               # [0, 1]
//   height_file = "dem.tif"         # optional: single-channel elevation image (relative to the
//                                   #   experiment file), read through OpenImageIO
//   frames = 80                     # camera path frames, 1..100000
//   path_seed = 1                   # camera path, 0..2^63-1
//   flight_height = 60              # metres above the highest nearby ground, [0, 100000]
//   look_ahead = 200                # metres, (0, 100000]
//   repetitions = 3                 # timed draws per (frame, tau) and of the full mesh, 1..1000
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "terrain_lod/bisection_hierarchy.h"
#include "terrain_lod/screen_error_metric.h"
#include "scenes/study_settings.h"

namespace ra::lod {

struct LodSettings : scenes::StudySettings {  // file, name, camera
  std::string title = "Terrain level of detail";
  std::string platform = "osmesa-llvmpipe";
  std::vector<double> tau{0.5, 1, 2, 4, 8};
  LambdaKind lambda = LambdaKind::kWindow;
  std::vector<LambdaKind> check_lambdas{LambdaKind::kPlanar, LambdaKind::kSpherical};
  ErrorPropagation propagation = ErrorPropagation::kNested;
  bool equalise_seams = true;
  int tile_size = 257;
  int tiles_x = 2, tiles_y = 2;
  scenes::TerrainParams terrain;  // seed, spacing, height_scale, feature_size, octaves, persistence
  std::string height_file;  // resolved against the experiment file's folder; empty: generated
  int frames = 80;
  uint64_t path_seed = 1;
  double flight_height = 60;
  double look_ahead = 200;
  int repetitions = 3;

  LodSettings();
};

// The largest terrain (vertices, (tiles_x (tile_size - 1) + 1) (tiles_y (tile_size - 1) + 1)) a
// study accepts, generated or read from a height_file after cropping: 2^24 = 16 777 216. Reasons:
// vertex numbers are int / uint32 and edge keys u << 32 | v (safe far beyond this); the per-vertex
// arrays (heights, z_lod, three error arrays, GL vertices) take about 60 bytes per vertex, 1 GB at
// this size; and every frame the checks walk every vertex (screen error, seams) for every lambda
// and tau, which on a 2-core CI machine already takes seconds per frame at this size.
constexpr int64_t kMaxTerrainVertices = int64_t(1) << 24;

// Reads and validates `path`; throws UserError (file:line:column).
LodSettings read_lod_experiment(const std::string& path);
LodSettings parse_lod_experiment(const std::string& text, const std::string& path);

}  // namespace ra::lod
