// Camera paths through a scene for the per-frame measurements (Wimmer & Wonka 2003, section 7.2:
// "we recorded a path through the test scenes"): generated (a seeded, smooth Catmull-Rom walk) or
// read from a CSV file of recorded viewpoints.
// Units: metres, world coordinates, +Z up.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace ra::scenes {

struct CameraPathParams {
  uint64_t seed = 1;
  int frames = 500;            // viewpoints, 1..1000000
  int waypoints = 12;          // seeded waypoints the path passes through, 2..10000
  double eye_height = 1.7;     // metres above the ground (city, forest: walking)
  double flight_height = 60;   // metres above the highest nearby ground (terrain: flying)
  double look_ahead = 20;      // metres: the target is this far ahead along the path
};

// A smooth path of `frames` viewpoints, evenly spaced by arc length, guided by seeded waypoints:
//   city (a layout with streets): a random walk over `waypoints` street crossings that never
//         turns back: straight along the centre lines, quarter circles of radius
//         min(0.45 street_width, pitch / 4) at turns, so eyes stay within street_width / 2 of a
//         centre line, at eye_height;
//   terrain (a layout with a ground grid): flying at flight_height above the highest vertex of
//         every grid cell within one spacing (then smoothed: never lower), looking ahead and
//         25 % of look_ahead down;
//   forest (and any other kind): walking at eye_height.
// Off the streets, a walker with turning radius free_flight_turn_radius() steers towards
// `waypoints` seeded points of the layout box's inner 80 %. Targets are look_ahead metres ahead.
// Eyes stay within the scene's layout box in x, y. Deterministic in (scene layout, params).
// Throws std::invalid_argument for parameters outside their range or a scene without a layout.
std::vector<Viewpoint> generate_camera_path(const Scene& scene, const CameraPathParams& params);

// The smallest turning radius of a path off the streets: 2.5 % of the layout box's smaller side
// (metres); the heading of such a path turns by at most 1 / radius radians per metre.
double free_flight_turn_radius(const SceneLayout& layout);

// The recorded-path format: a header line "frame,eye_x,eye_y,eye_z,target_x,target_y,target_z",
// then one line per frame numbered 0, 1, 2, ... in order; numbers in metres; up is +Z. Blank
// lines and lines starting with '#' are skipped.
// Throws UserError ("FILE:LINE: what is wrong") for a missing file, a wrong header, a wrong
// number of fields, a field that is not a finite number, frames out of sequence, eye == target,
// or no frames.
std::vector<Viewpoint> read_camera_path_csv(const std::string& path);
// Parses the text of such a file; `file_name` goes into error messages.
std::vector<Viewpoint> parse_camera_path_csv(const std::string& text, const std::string& file_name);
// Writes the same format, atomically (round-trips exactly: 17 significant digits); throws
// std::runtime_error naming the file when it cannot be written.
// Used by tests as the round trip of parse_camera_path_csv.
void write_camera_path_csv(const std::vector<Viewpoint>& path, const std::string& file);

}  // namespace ra::scenes
