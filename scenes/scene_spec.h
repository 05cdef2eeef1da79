// Scene declarations in an experiment file: a [[scene]] array of tables, each one scene of the
// rendering-time study with its camera path. Every key is checked; an unknown key, a wrong type or
// a value out of range is a UserError "FILE:LINE:COLUMN: scene[K].KEY = V is out of range
// (allowed: LO to HI)". Units: metres, world coordinates, +Z up (as in the generators).
//
//   [[scene]]
//   kind = "city"            # "city" | "terrain" | "forest"
//   name = "downtown"        # optional, default: the kind; unique among the scenes
//   seed = 7                 # optional, default 1
//   blocks_x = 40            # kind-specific sizes, see CityParams / TerrainParams / ForestParams
//   [scene.camera_path]      # optional
//   frames = 500             # a generated path (CameraPathParams keys) ...
//   seed = 3
//   # file = "walk.csv"      # ... or a recorded one, relative to the experiment file's folder
#pragma once

#include <string>
#include <vector>

#ifndef TOML_EXCEPTIONS
#define TOML_EXCEPTIONS 1
#endif
#include <toml++/toml.h>

#include "scenes/camera_path.h"
#include "scenes/city_scene.h"
#include "scenes/forest_scene.h"
#include "scenes/scene.h"
#include "scenes/terrain_scene.h"

namespace ra::scenes {

struct SceneSpec {
  std::string name;  // unique within the file
  std::string kind;  // "city", "terrain" or "forest": which of the params below applies
  CityParams city;
  TerrainParams terrain;
  ForestParams forest;
  CameraPathParams path;  // used when path_file is empty
  std::string path_file;  // a recorded path (CSV), resolved against the experiment file's folder
};

// The [[scene]] tables of `root`, in file order; empty when there is no `scene` key. Keys:
//   all:     kind, name, seed, camera_path
//   city:    blocks_x, blocks_y, buildings_per_block, textures, texture_size, block_size,
//            street_width, floors_min, floors_max, floor_height, bay_width, tiers_max
//   terrain: size, spacing, height_scale, feature_size, octaves, persistence, texture_size
//   forest:  trees, area, slices_min, slices_max, height_min, height_max, texture_size
//   camera_path: frames, seed, waypoints, eye_height, flight_height, look_ahead | file
// `file_name` is the experiment file's path: it starts every error message and anchors
// relative camera path files. Throws UserError.
std::vector<SceneSpec> parse_scene_specs(const toml::table& root, const std::string& file_name);

// The scene a spec declares (generate_city / generate_terrain / generate_forest).
Scene build_scene(const SceneSpec& spec);

// Its camera path: read from path_file when set, otherwise generated through `scene`.
std::vector<Viewpoint> build_camera_path(const SceneSpec& spec, const Scene& scene);

}  // namespace ra::scenes
