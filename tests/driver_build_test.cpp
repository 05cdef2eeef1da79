// One driver per record: every process that draws for a run (workers, the audit's re-render,
// `show`) loads the driver that made the run's records, or stops with exit status 2 naming both.
//
// The second build: where no Mesa other than the installed one is at hand (a fresh clone without
// the network), a run's "other build" is simulated honestly: a copy of a run whose driver file
// says another GL_VERSION and some of whose records have other pixels, exactly what a run made
// with another Mesa looks like on disk. Where a fetched build is present (RENDERAUDIT_TEST_BUILD,
// else the newest build of bookworm-backports in the build cache), the same is checked with it.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "platforms/driver_loading.h"
#include "rundir/build_record.h"
#include "tests/cli_harness.h"

namespace fs = std::filesystem;
using namespace ra::testing_cli;

namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

nlohmann::json read_json(const std::string& path) { return nlohmann::json::parse(read_text(path)); }

void write_json(const std::string& path, const nlohmann::json& j) {
  std::ofstream(path, std::ios::trunc) << j.dump(2) << "\n";
}

const char* kSimulatedVersion = "4.5 (Compatibility Profile) Mesa 99.0.0-simulated";

std::string small_experiment(const std::string& platforms) {
  return "seed = 5\nplatforms = [" + platforms +
         "]\n[views]\norientations = 1\nfov_deg = [30]\nwindows = [128]\nnear = 0.01\n"
         "far = 10.0\n[primitives]\nlines = 60\ntriangles = 60\n[run]\nshard_size = 1000\n";
}

// Makes DIR/cur a copy of DIR/base "made with another build": its driver file (and the manifest's
// copy) names another GL_VERSION, and the pixel hash of every 10th line differs. Returns the
// installed driver's GL_VERSION.
std::string simulate_other_build(const std::string& dir) {
  fs::copy(dir + "/base", dir + "/cur", fs::copy_options::recursive);
  const std::string driver = dir + "/cur/drivers/osmesa-llvmpipe.json";
  nlohmann::json d = read_json(driver);
  const std::string installed = d["version"];
  d["version"] = kSimulatedVersion;
  write_json(driver, d);
  nlohmann::json m = read_json(dir + "/cur/manifest.json");
  m["drivers"]["osmesa-llvmpipe"]["version"] = kSimulatedVersion;
  write_json(dir + "/cur/manifest.json", m);
  for (const auto& e : fs::directory_iterator(dir + "/cur/records")) {
    if (e.path().filename().string().find(".line.") == std::string::npos) continue;
    std::istringstream in(read_records_text(e.path().string()));
    std::string line, out;
    std::getline(in, line);
    out = line + "\n";
    std::size_t column = 0;  // of pixel_hash, by the header
    for (std::size_t at = 0; line.compare(at, 11, "pixel_hash,") != 0; at = line.find(',', at) + 1)
      ++column;
    for (int i = 0; std::getline(in, line);) {
      if (line.empty() || line[0] == '#') continue;
      if (i++ % 10 == 0) {  // other pixels: another pixel hash
        std::size_t begin = 0;
        for (std::size_t k = 0; k < column; ++k) begin = line.find(',', begin) + 1;
        const std::size_t end = line.find(',', begin);
        const uint64_t hash = std::stoull(line.substr(begin, end - begin));
        line.replace(begin, end - begin, std::to_string(hash + 1));
      }
      out += line + "\n";
    }
    write_records_text(e.path().string(), out);
    reseal_records_file(e.path().string());
  }
  return installed;
}

// A fetched Mesa build other than the installed one, or "" (the test then says why it skips).
std::string other_build_dir() {
  if (const char* d = std::getenv("RENDERAUDIT_TEST_BUILD"); d && *d) return d;
  return ra::rundir::cached_build_of_suite("bookworm-backports");
}

}  // namespace

// A run made with one build, audited from a process that loads another, is never called unchanged
// or flaky: the re-render stops with exit status 2 and names both drivers.
TEST(DriverBuild, AuditOfARunOfAnotherBuildIsNeverUnchangedOrFlaky) {
  const std::string dir = fresh_dir("driver_other_build");
  write_text(dir + "/e.toml", small_experiment("\"osmesa-llvmpipe\""));
  ASSERT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + dir + "/base --jobs 2 --quiet")
                .exit_code, 0);
  const std::string installed = simulate_other_build(dir);
  const Outcome o = run_renderaudit("audit " + dir + "/base " + dir + "/cur --no-history");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_EQ(o.output.find("unchanged"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("flakes"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("driver mismatch"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find(kSimulatedVersion), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("GL_VERSION '" + installed + "'"), std::string::npos) << o.output;
  // Without re-renders there is nothing to mismatch: the audit reports the changes as they are.
  const Outcome plain =
      run_renderaudit("audit " + dir + "/base " + dir + "/cur --no-history --max-rerenders 0");
  EXPECT_EQ(plain.exit_code, 1) << plain.output;
}

// A run resumed by a process with another driver stops (exit 2) before drawing a primitive, and
// `show` refuses to draw a record of it.
TEST(DriverBuild, ResumeAndShowWithAnotherDriverStop) {
  const std::string dir = fresh_dir("driver_resume");
  write_text(dir + "/e.toml", small_experiment("\"osmesa-llvmpipe\""));
  ASSERT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --jobs 1 --quiet")
                .exit_code, 0);
  const std::string driver = dir + "/run/drivers/osmesa-llvmpipe.json";
  nlohmann::json d = read_json(driver);
  d["version"] = kSimulatedVersion;
  write_json(driver, d);
  std::string removed;
  for (const auto& e : fs::directory_iterator(dir + "/run/records"))
    if (e.path().filename().string().find(".triangle.") != std::string::npos) removed = e.path();
  ASSERT_FALSE(removed.empty());
  fs::remove(removed);
  const Outcome resumed =
      run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --jobs 1 --quiet");
  EXPECT_EQ(resumed.exit_code, 2) << resumed.output;
  EXPECT_NE(resumed.output.find("driver mismatch"), std::string::npos) << resumed.output;
  EXPECT_FALSE(fs::exists(removed)) << "a shard was drawn with another driver";
  EXPECT_EQ(read_json(dir + "/run/manifest.json")["status"], "wrong-renderer");

  const Outcome shown = run_renderaudit("show " + dir + "/run --platform osmesa-llvmpipe --kind "
                                        "line --view 1 --index 3 --out " + dir + "/p.png");
  EXPECT_EQ(shown.exit_code, 2) << shown.output;
  EXPECT_NE(shown.output.find(kSimulatedVersion), std::string::npos) << shown.output;
  EXPECT_FALSE(fs::exists(dir + "/p.png"));
}

// A build's library changed after the run (64 bytes appended: the GL strings stay the same) stops a
// resumed run and `show` with exit status 2, naming the library: the driver file's fingerprints are
// compared, not only GL_RENDERER and GL_VERSION. The unchanged build resumes.
TEST(DriverBuild, AChangedBuildLibraryWithTheSameGlStringsStops) {
  const std::string installed = "/usr/lib/x86_64-linux-gnu/libOSMesa.so.8";
  if (!fs::exists(installed)) GTEST_SKIP() << "libosmesa6 is not installed";
  const std::string dir = fresh_dir("driver_tampered");
  fs::create_directories(dir + "/build");
  const std::string library = dir + "/build/libOSMesa.so.8";
  fs::copy_file(fs::canonical(installed), library);
  write_text(dir + "/e.toml", small_experiment("\"osmesa-llvmpipe@mine\"") +
                                  "[builds.mine]\ndir = \"" + dir + "/build\"\n");
  const std::string run = "run " + dir + "/e.toml --out " + dir + "/run --jobs 1 --quiet";
  ASSERT_EQ(run_renderaudit(run).exit_code, 0);
  std::vector<std::string> shards;
  for (const auto& e : fs::directory_iterator(dir + "/run/records")) shards.push_back(e.path());
  ASSERT_EQ(shards.size(), 2u);
  fs::remove(shards[0]);
  const Outcome same = run_renderaudit(run);
  EXPECT_EQ(same.exit_code, 0) << same.output;
  EXPECT_TRUE(fs::exists(shards[0]));

  std::ofstream(library, std::ios::app | std::ios::binary) << std::string(64, 'x');
  fs::remove(shards[1]);
  const Outcome resumed = run_renderaudit(run);
  EXPECT_EQ(resumed.exit_code, 2) << resumed.output;
  EXPECT_NE(resumed.output.find("driver mismatch: osmesa-llvmpipe@mine: library " + library +
                                " has fingerprint"), std::string::npos) << resumed.output;
  EXPECT_FALSE(fs::exists(shards[1])) << "a shard was drawn with a changed library";
  const Outcome shown = run_renderaudit("show " + dir + "/run --platform osmesa-llvmpipe@mine "
                                        "--kind line --view 1 --index 3 --out " + dir + "/p.png");
  EXPECT_EQ(shown.exit_code, 2) << shown.output;
  EXPECT_NE(shown.output.find(library), std::string::npos) << shown.output;
  EXPECT_FALSE(fs::exists(dir + "/p.png"));
}

// With a real second build: one run draws with the installed Mesa and with the build; its driver
// files name each one's libraries; the audit between them is the same whether the audit process's
// environment points at the build or not.
TEST(DriverBuild, TwoBuildsInOneRunAuditTheSameInAnyEnvironment) {
  const std::string build = other_build_dir();
  if (build.empty() || !fs::exists(ra::rundir::build_library_dir(build) + "/libOSMesa.so.8"))
    GTEST_SKIP() << "no second Mesa build here: `renderaudit builds fetch bookworm-backports` "
                    "(needs the Debian registry) or RENDERAUDIT_TEST_BUILD=DIR enables this test";
  const std::string dir = fresh_dir("driver_two_builds");
  // FOV 30 at 907 x 907: where llvmpipe 25.0 draws lines differently from 22.3
  std::string text = small_experiment("\"osmesa-llvmpipe\", \"osmesa-llvmpipe@other\"") +
                     "[builds.other]\ndir = \"" + build + "\"\n";
  text.replace(text.find("windows = [128]"), 15, "windows = [907]");
  write_text(dir + "/e.toml", text);
  const Outcome r = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --jobs 2 --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json a = read_json(dir + "/run/drivers/osmesa-llvmpipe.json");
  const nlohmann::json b = read_json(dir + "/run/drivers/osmesa-llvmpipe@other.json");
  EXPECT_NE(a["version"], b["version"]);
  EXPECT_EQ(b["build"]["name"], "other");
  bool build_library = false;
  for (const auto& l : b["build"]["libraries"])
    build_library |= l["path"].get<std::string>().rfind(fs::canonical(build).string(), 0) == 0 &&
                     l["fnv1a64"].get<std::string>().size() == 16;
  EXPECT_TRUE(build_library) << b.dump(2);

  const std::string audit = "audit " + dir + "/run --between osmesa-llvmpipe osmesa-llvmpipe@other "
                            "--no-history --out ";
  const Outcome plain = run_renderaudit(audit + dir + "/a1");
  const std::string lib = ra::rundir::build_library_dir(build);
  const Outcome polluted = run_command("env LD_LIBRARY_PATH=" + lib + " RENDERAUDIT_LIBOSMESA=" +
                                       lib + "/libOSMesa.so.8 " + RA_BINARY + " " + audit + dir +
                                       "/a2");
  EXPECT_NE(plain.exit_code, 0) << plain.output;
  const nlohmann::json j1 = read_json(dir + "/a1/audit.json");
  std::printf("[ two builds ] %s: %d changed, %d flakes\n", j1["verdict"].get<std::string>().c_str(),
              int(j1["counts"]["changed"]), int(j1["counts"]["flakes"]));
  EXPECT_EQ(j1["counts"]["flakes"], 0);
  // The installed platform's re-render in the polluted environment loads the build and stops.
  if (polluted.exit_code == 2) {
    EXPECT_NE(polluted.output.find("driver mismatch"), std::string::npos) << polluted.output;
  } else {
    EXPECT_EQ(polluted.exit_code, plain.exit_code) << polluted.output;
    const nlohmann::json j2 = read_json(dir + "/a2/audit.json");
    EXPECT_EQ(j2["verdict"], j1["verdict"]);
    EXPECT_EQ(j2["counts"]["changed"], j1["counts"]["changed"]);
    EXPECT_EQ(j2["counts"]["flakes"], 0);
  }
}

// The ELF reader the loader orders libraries by, against the installed libOSMesa as readelf sees it.
TEST(DriverBuild, ElfDependenciesMatchReadelf) {
  const std::string lib = "/usr/lib/x86_64-linux-gnu/libOSMesa.so.8";
  if (!fs::exists(lib)) GTEST_SKIP() << "libosmesa6 is not installed";
  const ra::platforms::ElfDependencies d = ra::platforms::read_elf_dependencies(fs::canonical(lib));
  EXPECT_EQ(d.soname, "libOSMesa.so.8");
  const std::string readelf = shell_output("readelf -d " + fs::canonical(lib).string());
  if (readelf.empty()) GTEST_SKIP() << "readelf (binutils) is not installed";
  int needed = 0;
  for (std::size_t at = 0; (at = readelf.find("(NEEDED)", at)) != std::string::npos; ++at) ++needed;
  EXPECT_EQ(int(d.needed.size()), needed);
  for (const std::string& n : d.needed)
    EXPECT_NE(readelf.find("[" + n + "]"), std::string::npos) << n;
  EXPECT_TRUE(ra::platforms::read_elf_dependencies("/etc/hostname").soname.empty());
}

// `builds fetch` from a registry that cannot be reached: a clear error, and the cache as it was.
TEST(DriverBuild, FetchFromAnUnreachableRegistryLeavesTheCacheAsItWas) {
  if (shell_output("apt-get --version").empty()) GTEST_SKIP() << "apt-get is not installed";
  const std::string dir = fresh_dir("driver_fetch_unreachable");
  fs::create_directories(dir + "/cache");
  write_text(dir + "/cache/keep.txt", "a file of the user's\n");
  const Outcome o = run_renderaudit("builds fetch bookworm-backports --mirror http://127.0.0.1:9/debian "
                                    "--cache " + dir + "/cache");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("suite 'bookworm-backports' of http://127.0.0.1:9/debian is unreachable"),
            std::string::npos) << o.output;
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(dir + "/cache")) left.push_back(e.path().filename());
  EXPECT_EQ(left, std::vector<std::string>{"keep.txt"});
  const Outcome list = run_renderaudit("builds list --cache " + dir + "/cache");
  EXPECT_EQ(list.exit_code, 0) << list.output;
  EXPECT_NE(list.output.find("no builds in"), std::string::npos) << list.output;
  const Outcome bad = run_renderaudit("builds fetch 'no/suite' --cache " + dir + "/cache");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("is not a Debian suite name"), std::string::npos) << bad.output;
}
