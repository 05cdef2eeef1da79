// `renderaudit reproduce RUN --platform P --kind K --view V --index I`: one record of a run as a
// small standalone C program a driver developer can build and run without this project. It
// draws the primitive as the worker did (EGL surfaceless, desktop GL compatibility profile, an
// RGBA8 framebuffer object of the view's size, the view's GL_PROJECTION and GL_MODELVIEW matrices
// loaded with glLoadMatrixd, glViewport over the window, white on black, width/size 1, no
// smoothing, blending, dithering, depth test or culling, glBegin/glVertex3d/glEnd with the
// vertices as hex floats, glFinish, glReadPixels of the whole window), then prints the pixels lit,
// their hash (the records' pixel_hash), the worker's count and hash, and the exact reference
// rasterizer's count; it exits 1 when its pixels differ from the reference's, 0 when they agree.
#pragma once

#include <cstdint>
#include <string>

namespace ra::audit {

struct ReproduceRequest {
  std::string run_dir, platform, kind;
  int view = 0;
  uint64_t index = 0;
};

struct Reproducer {
  std::string source;      // the C file
  std::string build_line;  // "cc repro.c -o repro -lEGL -lOpenGL"
  std::string run_line;    // the environment and the command that picks the run's driver
  uint64_t record_pixels = 0, record_hash = 0, reference_pixels = 0, reference_hash = 0;
  std::string violated_rules;  // the record's ('+'-joined rule names; empty when none)
  std::string view_text;       // "FOV 30 deg, 907 x 907"
};

// The environment that makes a reproducer draw with Mesa driver `mesa_driver` ("llvmpipe") of the
// build folder `build_dir` ("" for the installed Mesa): LD_LIBRARY_PATH at its library folder,
// LIBGL_DRIVERS_PATH where it has DRI drivers (Mesa before 24), software rendering, one thread.
std::string reproducer_environment(const std::string& build_dir, const std::string& mesa_driver);

// Throws UserError for a run, platform (aliased GL platforms only), kind, view or index the run
// has no record of.
Reproducer make_reproducer(const ReproduceRequest& request, const std::string& c_file_name);

}  // namespace ra::audit
