// Measurements of the rendering-time study (Wimmer & Wonka 2003), as the GL side records them and
// the estimation side fits them. Times are microseconds of wall-clock time; counts are per draw.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace ra::timing {

// One object drawn alone from one viewpoint (the paper's "test measurement of an object").
struct ObjectSample {
  int object = 0;              // index into Scene::objects
  double alpha = 0;            // radians: angle between the two supporting lines of the bounding
                               // sphere seen from the eye (clipped to the view frustum)
  double gamma = 0;            // radians, [0, 2 pi): azimuth of the eye around the object centre
  double phi = 0;              // radians, [-pi/2, pi/2]: elevation of the eye seen from the centre
  int64_t triangles = 0;       // #tris: triangles submitted (the whole object)
  int64_t vertices = 0;        // #v: vertices of the object
  int64_t transformed = 0;     // #tv: vertices transformed, by FIFO vertex-cache simulation
  int64_t pixels = 0;          // #pix: fragments that passed (occlusion query)
  int64_t state_changes = 0;   // texture binds issued for the object
  std::vector<double> cpu_us;  // every repetition: draw + glFinish on the CPU clock
  std::vector<double> gpu_us;  // every repetition: GL_TIME_ELAPSED; empty when unsupported
};

// One frame of a camera path: the measured frame time and what each visible object contributes.
struct FrameSample {
  int frame = 0;
  std::vector<ObjectSample> objects;  // objects after view-frustum culling, with their counts
  std::vector<double> cpu_us;         // every repetition of the whole frame
  std::vector<double> gpu_us;         // every repetition; empty when unsupported
};

}  // namespace ra::timing
