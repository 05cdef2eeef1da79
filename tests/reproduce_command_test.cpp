// `renderaudit reproduce`: the C program it writes, built with cc and run, lights exactly the
// pixels the worker recorded (the records' pixel count and pixel_hash), on the installed llvmpipe.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "tests/cli_harness.h"

namespace fs = std::filesystem;
using namespace ra::testing_cli;

namespace {

struct Drawn {
  int exit_code = -1;
  unsigned long long pixels = 0, hash = 0, worker_pixels = 0, worker_hash = 0, ref_pixels = 0,
                     ref_hash = 0;
  std::string output;
};

// Writes, builds and runs the reproducer of one record.
Drawn reproduce(const std::string& dir, const std::string& platform, const std::string& kind,
                int view, int index) {
  Drawn d;
  const std::string c = dir + "/" + platform + "." + kind + "." + std::to_string(view) + "." +
                        std::to_string(index) + ".c";
  const Outcome w = run_renderaudit("reproduce " + dir + "/run --platform " + platform +
                                    " --kind " + kind + " --view " + std::to_string(view) +
                                    " --index " + std::to_string(index) + " --out " + c);
  EXPECT_EQ(w.exit_code, 0) << w.output;
  const std::string exe = c.substr(0, c.size() - 2);
  const Outcome cc = run_command("cc -std=c99 -Wall -Werror " + c + " -o " + exe + " -lEGL -lOpenGL");
  EXPECT_EQ(cc.exit_code, 0) << cc.output;
  const std::string driver = platform.find("softpipe") != std::string::npos ? "softpipe" : "llvmpipe";
  const Outcome run = run_command("env LIBGL_ALWAYS_SOFTWARE=1 GALLIUM_DRIVER=" + driver +
                                  " LP_NUM_THREADS=0 " + exe);
  d.exit_code = run.exit_code;
  d.output = run.output;
  std::smatch m;
  const auto read = [&](const char* label, unsigned long long* n, unsigned long long* h) {
    if (std::regex_search(run.output, m, std::regex(std::string(label) + " +([0-9]+) \\(hash ([0-9]+)\\)")))
      *n = std::stoull(m[1]), *h = std::stoull(m[2]);
    else
      ADD_FAILURE() << "no '" << label << "' line in: " << run.output;
  };
  read("pixels lit", &d.pixels, &d.hash);
  read("worker", &d.worker_pixels, &d.worker_hash);
  read("reference", &d.ref_pixels, &d.ref_hash);
  return d;
}

}  // namespace

TEST(ReproduceCommand, TheCProgramLightsTheWorkersPixelsExactly) {
  if (shell_output("cc --version").empty()) GTEST_SKIP() << "no C compiler (cc) here";
  const std::string dir = fresh_dir("reproduce");
  // FOV 30 and 150 at 128 and 907: near and wide cameras, small and large windows.
  write_text(dir + "/e.toml",
             "seed = 7\nplatforms = [\"egl-llvmpipe\", \"osmesa-llvmpipe\"]\n[views]\n"
             "orientations = 1\nfov_deg = [30, 150]\nwindows = [128, 907]\nnear = 0.01\n"
             "far = 10.0\n[primitives]\npoints = 4\nlines = 4\ntriangles = 4\n");
  const Outcome r = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --jobs 2 --quiet");
  if (r.exit_code == 2 && r.output.find("egl-llvmpipe") != std::string::npos)
    GTEST_SKIP() << "EGL cannot draw here: " << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  int differing = 0, drawn = 0;
  for (const std::string platform : {"egl-llvmpipe", "osmesa-llvmpipe"})
    for (const std::string kind : {"point", "line", "triangle"})
      for (int view = 1; view <= 4; ++view)
        for (int index : {0, 3}) {
          const Drawn d = reproduce(dir, platform, kind, view, index);
          SCOPED_TRACE(platform + " " + kind + " view " + std::to_string(view) + " index " +
                       std::to_string(index));
          EXPECT_EQ(d.pixels, d.worker_pixels) << d.output;
          EXPECT_EQ(d.hash, d.worker_hash) << d.output;
          // exit 1 exactly when the pixels differ from the reference's
          EXPECT_EQ(d.exit_code, d.hash == d.ref_hash && d.pixels == d.ref_pixels ? 0 : 1) << d.output;
          differing += d.exit_code == 1;
          drawn += d.pixels > 0;
        }
  std::printf("[ reproduce ] 48 records: %d drew pixels, %d differ from the reference\n", drawn,
              differing);
  EXPECT_GT(drawn, 0);
}
