// `renderaudit reproduce RUN --platform P --kind K --view V --index I`: one record of a run as a
// small standalone C program a driver developer can build and run without this project. It
// draws the primitive as the worker did (EGL surfaceless, desktop GL compatibility profile, an
// RGBA8 framebuffer object of the view's size, the view's GL_PROJECTION and GL_MODELVIEW matrices
// loaded with glLoadMatrixd, glViewport over the window, white on black, width/size 1, no
// smoothing, blending, dithering, depth test or culling, glBegin/glVertex3d/glEnd with the
// vertices as hex floats, glFinish, glReadPixels of the whole window), then prints the pixels lit,
// their hash (the records' pixel_hash), the worker's count and hash, the exact reference
// rasterizer's, and a verdict. A difference from the reference is not a fault by itself: GL lets
// an implementation snap and round (metrics/conformance.h), and the C program cannot judge that
// itself. It knows the run's verdict of the worker's pixels, so it judges what it can:
//   0  its pixels are the reference's, or the worker's and the run found them allowed by GL;
//   1  its pixels are the worker's and the run found them breaking GL's rules;
//   3  its pixels are neither (another driver or build drew them): not judged
//      (`renderaudit show` draws a primitive with any platform and judges it);
//   2  EGL or GL failed.
// The program is built beside its C file (FILE.c -> FILE), so the printed build and run lines
// paste in any folder.
#pragma once

#include <cstdint>
#include <string>

#include "metrics/records.h"

namespace ra::audit {

// The reproducer's exit codes (above).
constexpr int kReproducerAllowed = 0, kReproducerViolation = 1, kReproducerFailed = 2,
              kReproducerNotJudged = 3;

// What the C program says, and exits with, when it draws the worker's pixels: the run's verdict of
// them ("allowed by GL (within-spec)", "breaking GL's rules (line-deviation)").
struct ReproducerVerdict {
  int exit_code = kReproducerNotJudged;
  std::string text;
};
ReproducerVerdict reproducer_verdict(metrics::Conformance conformance,
                                     const std::string& violated_rules);

// The program built from C file `c_file_name`: beside it, without the .c (".out" added to a name
// without an extension, never the C file itself).
std::string reproducer_program(const std::string& c_file_name);

struct ReproduceRequest {
  std::string run_dir, platform, kind;
  int view = 0;
  uint64_t index = 0;
};

struct Reproducer {
  std::string source;      // the C file
  std::string program;     // reproducer_program(C file): "RUN/reproduce/P.line.v5.721"
  std::string build_line;  // "cc DIR/P.line.v5.721.c -o DIR/P.line.v5.721 -lEGL -lOpenGL"
  std::string run_line;    // the environment that picks the run's driver, and the program
  ReproducerVerdict verdict;  // the run's verdict of the worker's pixels
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
