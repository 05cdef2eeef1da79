// `renderaudit reproduce`: the C program it writes, built with cc and run, lights exactly the
// pixels the worker recorded (the records' pixel count and pixel_hash), on the installed llvmpipe,
// and its exit code says what GL allows: a difference from the reference the run found allowed is
// not a failure.
#include <gtest/gtest.h>
#include <sys/mount.h>

#include <cerrno>
#include <cstring>

#include <filesystem>
#include <fstream>
#include <map>
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
  std::string output, exe;
};

// Runs a built reproducer with Mesa's driver `driver` and reads the counts it prints.
void draw(Drawn& d, const std::string& driver) {
  const Outcome run = run_command("env LIBGL_ALWAYS_SOFTWARE=1 GALLIUM_DRIVER=" + driver +
                                  " LP_NUM_THREADS=0 " + d.exe);
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
}

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
  d.exe = c.substr(0, c.size() - 2);
  const Outcome cc = run_command("cc -std=c99 -Wall -Werror " + c + " -o " + d.exe + " -lEGL -lOpenGL");
  EXPECT_EQ(cc.exit_code, 0) << cc.output;
  draw(d, platform.find("softpipe") != std::string::npos ? "softpipe" : "llvmpipe");
  return d;
}

// The run's verdict of each record of one platform, kind and view: index -> conformance.
std::map<int, std::string> conformance_of(const std::string& run, const std::string& platform,
                                          const std::string& kind, int view) {
  const Outcome o = run_renderaudit("records " + run + " --platform " + platform + " --kind " +
                                    kind + " --view " + std::to_string(view) +
                                    " --columns index,conformance");
  EXPECT_EQ(o.exit_code, 0) << o.output;
  std::map<int, std::string> out;
  std::istringstream lines(o.output);
  std::string line;
  std::getline(lines, line);  // the header
  while (std::getline(lines, line)) {
    const std::size_t comma = line.find(',');
    if (comma != std::string::npos) out[std::stoi(line.substr(0, comma))] = line.substr(comma + 1);
  }
  return out;
}

// What the reproducer is to exit with for the pixels it drew: 0 the reference's, or the worker's
// allowed by GL; 1 the worker's breaking GL's rules; 3 neither (not judged).
int expected_exit(const Drawn& d, const std::string& conformance) {
  if (d.pixels == d.ref_pixels && d.hash == d.ref_hash) return 0;
  if (d.pixels != d.worker_pixels || d.hash != d.worker_hash) return 3;
  return conformance == "violation" ? 1 : 0;
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
  int differing = 0, allowed = 0, drawn = 0, elsewise = 0;
  for (const std::string platform : {"egl-llvmpipe", "osmesa-llvmpipe"})
    for (const std::string kind : {"point", "line", "triangle"})
      for (int view = 1; view <= 4; ++view) {
        const std::map<int, std::string> verdicts =
            conformance_of(dir + "/run", platform, kind, view);
        for (int index : {0, 3}) {
          Drawn d = reproduce(dir, platform, kind, view, index);
          SCOPED_TRACE(platform + " " + kind + " view " + std::to_string(view) + " index " +
                       std::to_string(index) + " (" + verdicts.at(index) + ")");
          EXPECT_EQ(d.pixels, d.worker_pixels) << d.output;
          EXPECT_EQ(d.hash, d.worker_hash) << d.output;
          // 0 for the reference's pixels or a difference the run found allowed by GL; 1 only for
          // pixels that break GL's rules
          EXPECT_EQ(d.exit_code, expected_exit(d, verdicts.at(index))) << d.output;
          const bool differs = d.hash != d.ref_hash || d.pixels != d.ref_pixels;
          differing += differs;
          allowed += differs && d.exit_code == 0;
          drawn += d.pixels > 0;
          // llvmpipe's lines drawn by softpipe (Bresenham, not llvmpipe's rasterizer): pixels the
          // run did not record are not judged (3) unless they happen to be the reference's.
          if (kind == "line") {
            draw(d, "softpipe");
            EXPECT_EQ(d.exit_code, expected_exit(d, verdicts.at(index))) << d.output;
            elsewise += d.exit_code == 3;
          }
        }
      }
  std::printf("[ reproduce ] 48 records: %d drew pixels, %d differ from the reference (%d of them "
              "as GL allows); %d of 16 lines drawn otherwise by softpipe\n",
              drawn, differing, allowed, elsewise);
  EXPECT_GT(drawn, 0);
  EXPECT_GT(allowed, 0) << "no record differs from the reference as GL allows: the exit for one is "
                           "not tested";
  EXPECT_GT(elsewise, 0) << "softpipe drew every line as llvmpipe or the reference";
}

// The printed build line puts the program beside its C file and the run line runs it from there,
// whatever the folder they are pasted in: nothing is written into the working folder.
TEST(ReproduceCommand, TheProgramIsBuiltBesideItsCFile) {
  if (shell_output("cc --version").empty()) GTEST_SKIP() << "no C compiler (cc) here";
  const std::string dir = fresh_dir("reproduce_beside");
  write_text(dir + "/e.toml",
             "seed = 7\nplatforms = [\"osmesa-llvmpipe\"]\n[views]\norientations = 1\n"
             "fov_deg = [30]\nwindows = [128]\nnear = 0.01\nfar = 10.0\n[primitives]\nlines = 2\n");
  ASSERT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --quiet").exit_code, 0);
  fs::create_directories(dir + "/elsewhere");
  for (const std::string& out : std::vector<std::string>{"", " --out " + dir + "/mine.c"}) {
    const Outcome o = run_renderaudit("reproduce " + dir +
                                      "/run --platform osmesa-llvmpipe --kind line --view 1 "
                                      "--index 0" + out);
    ASSERT_EQ(o.exit_code, 0) << o.output;
    const std::string program =
        out.empty() ? dir + "/run/reproduce/osmesa-llvmpipe.line.v1.0" : dir + "/mine";
    std::smatch m;
    std::string build, run;
    if (std::regex_search(o.output, m, std::regex("\nbuild: ([^\n]*)\nrun: +([^\n]*)\n")))
      build = m[1], run = m[2];
    ASSERT_FALSE(build.empty()) << o.output;
    EXPECT_NE(o.output.find("worker: "), std::string::npos) << o.output;
    for (const std::string& line : {build, run}) {
      ra::util::ChildSpec sh;
      sh.argv = {"/bin/sh", "-c", line};
      sh.working_dir = dir + "/elsewhere";
      sh.stdin_null = true;
      sh.capture_output = true;
      const auto r = ra::util::run_program(sh);
      if (line == build) {
        EXPECT_TRUE(r.exited_ok()) << line << "\n" << r.output;
        EXPECT_TRUE(fs::exists(program)) << line;
      } else {
        EXPECT_NE(r.output.find("pixels lit"), std::string::npos) << line << "\n" << r.output;
        EXPECT_NE(r.output.find("verdict "), std::string::npos) << line << "\n" << r.output;
      }
    }
    EXPECT_TRUE(fs::is_empty(dir + "/elsewhere"))
        << "the program was built into the working folder";
  }
}

namespace {

// Runs renderaudit with an argument list as given (no word splitting: paths with newlines).
ra::util::ProgramResult run_args(std::vector<std::string> args) {
  args.insert(args.begin(), RA_BINARY);
  ra::util::ChildSpec spec;
  spec.argv = args;
  spec.stdin_null = true;
  spec.capture_output = true;
  return ra::util::run_program(spec);
}

// DIR/run: two lines of one view drawn by osmesa-llvmpipe.
bool two_line_run(const std::string& dir) {
  write_text(dir + "/e.toml",
             "seed = 7\nplatforms = [\"osmesa-llvmpipe\"]\n[views]\norientations = 1\n"
             "fov_deg = [30]\nwindows = [128]\nnear = 0.01\nfar = 10.0\n[primitives]\nlines = 2\n");
  return run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --quiet").exit_code == 0;
}

}  // namespace

// No input reaches generated code: an output path that closes the C comment and adds a statement
// (the folder it names exists) stays inside the comment, and the printed lines quote it.
TEST(ReproduceCommand, AHostileOutputPathStaysInsideTheCommentAndIsQuoted) {
  const std::string dir = fresh_dir("reproduce_hostile");
  ASSERT_TRUE(two_line_run(dir));
  fs::create_directories(dir + "/a*");
  // The folder "a*" makes the path hold "*/"; after it a line of C (no further '/').
  const std::string hostile =
      dir + "/a*/x\nint injected(void) { return system(\"touch pwned\"); }\n; touch pwned2 #.c";
  const auto r = run_args({"reproduce", dir + "/run", "--platform", "osmesa-llvmpipe", "--kind",
                           "line", "--view", "1", "--index", "0", "--out", hostile});
  ASSERT_EQ(r.exit_code(), 0) << r.output;
  std::ifstream in(hostile);
  const std::string c((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::istringstream lines(c);
  for (std::string l; std::getline(lines, l);) EXPECT_NE(l.rfind("int injected", 0), 0u) << l;
  // The C file compiles: its comments hold the path, not code.
  const std::string copy = dir + "/copy.c";
  fs::copy_file(hostile, copy);
  const Outcome cc = run_command("cc -std=c99 -Wall -Werror -fsyntax-only " + copy);
  EXPECT_EQ(cc.exit_code, 0) << cc.output;
  // The printed build line pastes as one argument: run it through a real shell.
  const std::size_t b = r.output.find("build: "), e = r.output.find("\nrun:");
  ASSERT_NE(b, std::string::npos);
  const std::string build_line = r.output.substr(b + 7, e - b - 7);
  ra::util::ChildSpec sh;
  sh.argv = {"/bin/sh", "-c", build_line};
  sh.working_dir = dir;
  sh.stdin_null = true;
  sh.capture_output = true;
  const auto built = ra::util::run_program(sh);
  EXPECT_TRUE(built.exited_ok()) << build_line << "\n" << built.output;
  EXPECT_FALSE(fs::exists(dir + "/pwned"));
  EXPECT_FALSE(fs::exists(dir + "/pwned2"));  // the `; touch` of the path did not run
}

TEST(ReproduceCommand, BadIndexAndOutputAreRefusedWithTheirReason) {
  const std::string dir = fresh_dir("reproduce_bad_input");
  ASSERT_TRUE(two_line_run(dir));
  const std::string base = "reproduce " + dir + "/run --platform osmesa-llvmpipe --kind line --view 1 ";
  for (const char* index : {"-1", "18446744073709551616"}) {
    const Outcome o = run_renderaudit(base + "--index " + index);
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_NE(o.output.find("not a primitive index"), std::string::npos) << o.output;
  }
  const Outcome folder = run_renderaudit(base + "--index 0 --out " + dir);
  EXPECT_EQ(folder.exit_code, 2) << folder.output;
  EXPECT_NE(folder.output.find("is a folder"), std::string::npos) << folder.output;
  const Outcome missing = run_renderaudit(base + "--index 0 --out " + dir + "/no/such/r.c");
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find("does not exist"), std::string::npos) << missing.output;
  EXPECT_FALSE(fs::exists(dir + "/no"));
}

// A full disk under --out is said with the file and the system's reason, exit 2 as for other
// output that cannot be written; nothing is left behind.
TEST(ReproduceCommand, AFullDiskIsSaidWithExit2) {
  const std::string dir = fresh_dir("reproduce_full_disk");
  ASSERT_TRUE(two_line_run(dir));
  const std::string mnt = dir + "/small";
  fs::create_directories(mnt);
  if (::mount("tmpfs", mnt.c_str(), "tmpfs", 0, "size=64k") != 0)
    GTEST_SKIP() << "cannot mount a tmpfs here (not root?): " << std::strerror(errno);
  {
    std::ofstream fill(mnt + "/fill", std::ios::binary);
    const std::string block(4096, 'x');
    for (int i = 0; i < 64 && fill; ++i) fill << block << std::flush;
  }
  const Outcome o = run_renderaudit("reproduce " + dir +
                                    "/run --platform osmesa-llvmpipe --kind line --view 1 --index 0"
                                    " --out " + mnt + "/r.c");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("reproduce: cannot write " + mnt + "/r.c: "), std::string::npos)
      << o.output;
  EXPECT_NE(o.output.find("No space left on device"), std::string::npos) << o.output;
  for (const auto& e : fs::directory_iterator(mnt))
    EXPECT_EQ(e.path().filename(), "fill") << e.path();
  ::umount(mnt.c_str());
}

TEST(Commands, AMistypedCommandIsNamedWithTheNearestOne) {
  for (const char* args : {"analyse /tmp", "analyse --help", "reprodce x"}) {
    const Outcome o = run_renderaudit(args);
    EXPECT_EQ(o.exit_code, 2) << args << ": " << o.output;
    EXPECT_NE(o.output.find("unknown command"), std::string::npos) << o.output;
  }
  EXPECT_NE(run_renderaudit("analyse /tmp").output.find("did you mean 'analyze'?"), std::string::npos);
  EXPECT_NE(run_renderaudit("reprodce x").output.find("did you mean 'reproduce'?"), std::string::npos);
  EXPECT_EQ(run_renderaudit("zzzzzzzz").output.find("did you mean"), std::string::npos);
}
